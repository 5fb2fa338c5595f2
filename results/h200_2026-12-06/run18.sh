#!/usr/bin/env bash
# Device run 18 of 2026-12-06 (session 50): every cell test case on NVIDIA, one process each
# (in one process the validated contexts after the 23rd cannot be created there), so the
# shallow sweep's tile test and the other late cases run on a GPU too.
#   build-carry/new/vkcollide_cells_tests at f12968a (the tiled sweep)
for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig
tar -xJf build-pack/bins.tar.xz
export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
W=/tmp/run18; mkdir -p $W
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $W/gpu.txt 2>&1
T=build-carry/new/vkcollide_cells_tests
$T --list-test-names-only | grep -v '^$' | sed 's/,/\\,/g; s/\[/\\[/g; s/\]/\\]/g' > $W/names.txt
while IFS= read -r n; do
  timeout 120 $T "$n" > $W/case.txt 2>&1; rc=$?
  echo "rc=$rc $(grep -E 'All tests passed|test cases' $W/case.txt | head -1) :: $n" >> $W/cases.txt
  [ $rc -ne 0 ] && cat $W/case.txt >> $W/failures.txt
done < $W/names.txt
rm -f $W/case.txt; tar -C /tmp -czf $OUT/run18.tgz run18
cat $W/cases.txt
