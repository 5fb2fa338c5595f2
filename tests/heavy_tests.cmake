# The tests that take longest in CI (seconds on two busy cores under ASan + UBSan, lavapipe
# with validation; 2026-12-04): CTest starts them first (COST), so that none of them begins
# near the end and leaves one core idle for minutes. CTest's own cost file cannot do
# it for us: it cuts test names at the first space. A name that is no longer a test is
# ignored; a new slow test belongs here.
set(VKCOLLIDE_TEST_COSTS
  "the reliable method finds every pair of every edge case, touching included=240"
  "default settings find every pair and the paper's method keeps its floors on reduced bench scenes, with 100 % precision=169"
  "device pairs: the GPU's sorted pairs equal DetectResult::pairs on every scene=146"
  "at 64 rays three axes or dilation find every pair of the recall guard's scenes=128"
  "the largest resolution this device holds runs with the validation layer quiet=83"
  "coordinates inside the sampling range give the pair on both backends, beyond it a named error=79"
  "vkcollide detect: errors name the option and the problem=75"
  "exact decision: GPU and CPU agree on the test scenes and the stability cases=64"
  "coplanar overlapping triangles and touching ones=56"
  "device pairs without a host result hold the host result's pairs=52"
  "reliable: coordinates from subnormal to 2^62 give the pair or a named error=51"
  "contact geometry: every pair of the test scenes gets a contact on both triangles=49"
  "vkcollide detect: per-file transforms compose in order and place the objects=39"
  "a detection that runs out of time fails with Timeout, the world is Busy, then works again=37"
)

# Tests of the executables the sanitized build runs (vkcollide_add_test SANITIZED) that run
# in the Release build instead: scene sweeps and closed-form checks that run the same host
# code as those executables' other tests (which stay under ASan), on more scenes or at
# sizes where ASan's allocator dominates (up to 146 s under ASan). Under ASan a GPU test
# costs 3-9 s, most of it lavapipe's allocations through ASan's allocator; in Release 1 s.
set(VKCOLLIDE_RELEASE_ONLY_TESTS
  "the largest resolution this device holds runs with the validation layer quiet"
  "device pairs: the GPU's sorted pairs equal DetectResult::pairs on every scene"
  "device pairs without a host result hold the host result's pairs"
  "proximity: a folded self-touching cloth over a ball, every pair within d found, none beyond the band"
  "proximity: adversarial contacts exactly at d, on edges, degenerate and coincident"
  "proximity: scales from 1e-6 to 1e6"
  # GPU loops of thousands of partners and double arithmetic over many cases: the device
  # pairs', responses' and proximity's host code is the other tests' (overflow, filter,
  # slots, refusals; capacity and settings)
  "device responses: tiny tilts, extreme scales, slivers and crowded triangles give the host's responses to the bit"
  "proximity: a vertex near 5,000 triangles gives its records in order, or on llvmpipe fails naming the loop limit"
  # the contact stage's host code: the other contacts tests (overflow rerun, both methods
  # and the pair filter, bad settings, two slots)
  "contacts: two spheres give the lens volume, centroid, centre-line normal and depth r1 + r2 - d"
  "contacts: a box inside a box is contained, with the inner box's volume and no normal"
  "contacts: a sphere half sunk into a box gives half its volume, the face normal and depth r"
  "contacts: nested spheres grow the ray lists and every pair is contained"
  # peeling's host code: the CPU-reference, packing, cap and depth-aware tests
  "a resolution past the framebuffer limit samples in compute or is refused by name"
  "depth-aware: a deep overlap downloads a fraction of the paper's triangles and loses no pair it finds"
  # the compute sampler's host code: tiles and lists, caps, ties, open cloth, depth-aware
  "compute sampling equals raster: spheres and a box, single and dual, 64 to 256"
  "compute sampling equals raster with depth-aware separation: every scene above"
  "compute sampling equals raster: interlocked tori and a twisted tube"
  # the loop-limit tests that run whole passes at 1024 to 4096 (their host code is the
  # other tests'; lavapipe's 128 MiB buffers and 401 objects cost most under ASan)
  "compute sampling equals raster on a triangle whose box takes several tiles per work item"
  "contacts: a face whose tiles take several per work item is drawn in full"
  "contacts: a ray through 400 stacked slabs gives every slab's volume, or on llvmpipe a named loop limit"
  "depth-aware bounds: edge-on slivers across a 4096^2 image reach every ray, or flag the loop limit"
  "compute sampling: a work item of 100,000 tiles draws them all, or flags the loop limit"
)

# Writes `script`: for each test of `target` (once CTest knows them) its labels (`labels`
# and `runs_in`, release or sanitized; release for the tests listed above) and, for those
# in VKCOLLIDE_TEST_COSTS, its COST.
function(vkcollide_write_test_properties target script labels runs_in)
  set(body "foreach(t IN LISTS ${target}_TESTS)\n  set(runs_in ${runs_in})\n")
  foreach(name ${VKCOLLIDE_RELEASE_ONLY_TESTS})
    string(APPEND body "  if(t STREQUAL \"${name}\")\n    set(runs_in release)\n  endif()\n")
  endforeach()
  string(APPEND body "  set_tests_properties(\"\${t}\" PROPERTIES LABELS \"${labels};\${runs_in}\")\n")
  foreach(entry ${VKCOLLIDE_TEST_COSTS})
    string(FIND "${entry}" "=" at REVERSE)
    string(SUBSTRING "${entry}" 0 ${at} name)
    math(EXPR from "${at} + 1")
    string(SUBSTRING "${entry}" ${from} -1 cost)
    string(APPEND body "  if(t STREQUAL \"${name}\")\n    set_tests_properties(\"\${t}\" PROPERTIES COST ${cost})\n  endif()\n")
  endforeach()
  string(APPEND body "endforeach()\n")
  file(WRITE ${script} "${body}")
endfunction()
