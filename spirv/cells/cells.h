// Data shared by the cell stage's shaders (GLSL) and its host side (C++,
// src/broad/cells/): buffer layouts, limits and flags. docs/reliable.md explains the
// method and why it cannot miss an intersecting pair.
//
// A grid of N x N cells covers the sampling image; cell (i, j) is the closed square
// [i, i+1] x [j, j+1] in cell units (sampling x, y times N), and the outermost cells
// reach to infinity, so every point of the plane lies in at least one cell. Each
// triangle is listed in every cell its padded projection may touch, with a depth
// interval that contains the depth of every point of it over that cell.
#ifndef VKCOLLIDE_CELLS_H
#define VKCOLLIDE_CELLS_H

#include "common/broadphase.h"  // VKC_ADDRESS, VKC_CONST, ObjectGpu, Projection

#ifdef __cplusplus
namespace vkcollide::gpu {
#endif

// Workgroup size of every cell-stage shader.
VKC_CONST kCellsGroupSize = 256;
// Cells per side: 1 .. kCellsMaxResolution (cell coordinates are packed in 16 bits).
VKC_CONST kCellsMaxResolution = 16384;
// A triangle whose clamped footprint box has at most this many cells is handled by one
// invocation; bigger ones are cut into work items of kCellsChunkCells box cells, one
// workgroup each (so a triangle spanning the grid does not serialise on one invocation).
VKC_CONST kCellsSmallBox = 64;
VKC_CONST kCellsChunkCells = 4096;
// Cells with at most kCellsSmallCell entries are swept in tiles (cells_sweep_shallow.glsl.inc:
// the cells that begin in one kCellsEntryChunk of entries, ordered by depth in shared memory);
// deeper cells by a workgroup that sorts them in shared memory (up to kCellsDeepShared
// entries); deeper still ("huge" cells), a workgroup sorts the cell in place in global
// memory (cells_deep_sort.comp) and workgroups of kCellsGroupSize sorted entries sweep it.
VKC_CONST kCellsSmallCell = 256;
// The scan records the cell of every kCellsEntryChunk-th entry (CellsParams.chunk_cells);
// the shallow sweep's tiles start from them and find each entry's cell between its chunk's
// first and the next one's. A tile is one workgroup: kCellsEntryChunk == kCellsGroupSize.
VKC_CONST kCellsEntryChunk = 256;
VKC_CONST kCellsDeepShared = 1024;
// The scan counts a huge cell deeper than this as every two of its entries (so any budget
// refuses it, 5.5e11 comparisons): one workgroup sorts a cell, which should end in a
// fraction of a second, and no invocation's candidates reach 2^20.
VKC_CONST kCellsHugeMax = 1048576u;
// Exchanges of the huge cells' sort per loop iteration (cells_deep_sort.comp): a loop
// guard counts iterations, not exchanges.
VKC_CONST kCellsSortExchangesPerIteration = 8u;
// The pair pass's canonical-cell check scans at most this many earlier cells of a pair;
// a pair whose scan runs out is kept (a duplicate the host removes), never dropped.
VKC_CONST kCellsDedupeBudget = 512;
// Cells with at least this many entries make the check's first part in the sweep
// (repeatsHere: no backward scan), before a candidate is written: a pair repeats in every
// cell both footprints share, and where footprints pile up (stacks, coincident copies,
// fans along the direction) those repeats were almost all of the candidates (a stack of
// 2,200 copies: 96.7M candidates, 94.3M duplicates). Shallower cells leave it to the pair
// pass.
VKC_CONST kCellsSweepDedupe = 64;
// Cells per workgroup of the scan (4 per invocation).
VKC_CONST kCellsScanBlock = 1024;
// A deep item whose chunk is this value sorts the whole cell in shared memory.
VKC_CONST kCellsSorted = 0xFFFFFFFFu;

// CellsTriangle.key: object index in the low 31 bits, and whether the object tests its own
// triangles against each other.
VKC_CONST kCellsKeySelf = 0x80000000u;
VKC_CONST kCellsKeyObject = 0x7FFFFFFFu;
// CellsEntry.key: with at most kCellsBoxedObjects objects, the object in bits 0-14, the
// self flag in bit 15 and the triangle's box within the entry's cell in bits 16-31
// (cellsSubBox); with more, the triangle's key and no box (entryKey in
// cells_common.glsl.inc).
VKC_CONST kCellsBoxedObjects = 32768u;
// CellsParams.object_flags
VKC_CONST kCellsObjectSelf = 1u;
VKC_CONST kCellsObjectDownload = 2u;  // geometry only on the GPU: survivors' triangles go to gpu_triangles

// CellsTriangle.mode
VKC_CONST kCellsEdges = 1u;  // coordinates are moderate: the per-cell edge tests apply
VKC_CONST kCellsPlane = 2u;  // the projection is not degenerate: per-cell depth from the plane

// CellsHeader.flags: what went wrong. The overflow flags ask the host to grow a buffer to
// the size the header reports and run again; the others are errors.
VKC_CONST kCellsOverflowEntries = 1u;
VKC_CONST kCellsOverflowItems = 2u;
VKC_CONST kCellsOverflowCandidates = 4u;
VKC_CONST kCellsOverflowSurvivors = 8u;
VKC_CONST kCellsBadIndex = 16u;        // an index >= the object's vertex count
VKC_CONST kCellsBadPosition = 32u;     // a position or transform entry not finite or >= 2^62
// A loop ran into CellsParams.loop_guard (a device that ends long loops silently): the
// run's result would be incomplete, so it fails naming the limit.
VKC_CONST kCellsLoopLimit = 64u;
VKC_CONST kCellsBadWorld = 128u;       // a world coordinate >= 2^62
VKC_CONST kCellsInconsistent = 256u;   // the fill found more footprints than the count (a bug)
VKC_CONST kCellsOverflowTriangles = 512u;  // gpu_triangles
VKC_CONST kCellsOverflowMask = 2575u;      // the four overflows above, kCellsOverflowTriangles and kCellsOverflowSorted
// Past the budget (CellsParams.budget): the footprint boxes span more cells than the budget
// (setup), or more pairs of footprints share a cell than kCellsComparisonsPerBudget times
// it (scan). Later passes do nothing; the host reports LimitExceeded, never grows a buffer
// for it. (Candidates beyond the budget are found by the host from the header's count.)
VKC_CONST kCellsOverBudget = 1024u;
// CellsParams.sorted is smaller than the huge cells' entries reach (CellsHeader.sorted_need).
VKC_CONST kCellsOverflowSorted = 2048u;

// The budget bounds the stage's memory and time: footprint box cells (so footprints) and
// candidate pairs at most CellsParams.budget each, and the sweep's comparisons at most this
// many times the budget (a comparison costs far less than a candidate, which is written,
// deduplicated and filtered). A cell of k <= kCellsDeepShared entries counts k (k - 1) / 2
// comparisons (scan); a huge cell counts its sort, k L (L + 1) / 4 with L = ceil(log2 k)
// (scan), k times the objects in it (the sort's runs, cells_deep_sort.comp) and the pairs
// its sweep visits (cells_deep.comp), so the count of a huge cell grows while it is swept.
VKC_CONST kCellsComparisonsPerBudget = 64u;

// Per-cell counts after the fill (CellsParams.counts): the sweep sets this bit in a cell's
// count when it finds a candidate there, and the invocation that sets it counts the cell.
VKC_CONST kCellsCandidateBit = 0x80000000u;

// Inputs are refused at or above this magnitude (2^62): with them every intermediate of
// the setup stays finite in float (docs/reliable.md, "Assumptions").
VKC_CONST kCellsMaxExponentBits = 189u;  // biased exponent of 2^62

// Slots of CellsParams.args (VkDispatchIndirectCommand each).
VKC_CONST kCellsArgsBig = 0u;    // big-triangle work items (count and fill)
VKC_CONST kCellsArgsSweep = 1u;  // one workgroup per kCellsEntryChunk entries (a tile)
VKC_CONST kCellsArgsDeep = 2u;   // deep-cell work items
VKC_CONST kCellsArgsPairs = 3u;  // one invocation per candidate (passes after the pair pass)
VKC_CONST kCellsArgsPairChunk = 4u;  // the pair pass: one invocation per candidate of its chunk
VKC_CONST kCellsArgsSort = 5u;  // the deep items again where there are huge cells to sort, else none
VKC_CONST kCellsArgsExact = 6u;  // the exact pass: one invocation per queued candidate of the chunk
VKC_CONST kCellsArgsCount = 7u;
// cells_args.comp's step for kCellsArgsExact (the others: 0, 1 and 2 + the pair chunk).
VKC_CONST kCellsArgsStepExact = 0xFFFFFFFFu;

// One triangle after setup (96 bytes: padded to whole 16-byte words, so that a record
// loads and stores as six vectors, not 21 scalars), written once, read by the count, fill
// and pair passes, so all of them see the same footprint and depth bounds bit for bit. The
// setup writes it word by word (packTriangle in cells_setup.glsl.inc): change both together.
struct CellsTriangle {
    float x[3];       // vertices in cell units (sampling x times N)
    float y[3];
    float z[3];       // sampling depth
    float pad;        // footprint padding in cell units: covers the GPU's rounding of world
                      // and sampling coordinates against the CPU's world positions
    float zmin, zmax; // depth range of the triangle, padded outward by ez
    float ez;         // depth padding (the same error bound along z)
    float gx, gy;     // depth plane: dz per cell along x and y (mode kCellsPlane)
    float egx, egy;   // bounds on the error of gx and gy
    uint cells_lo;    // first cell of the clamped footprint box: i | j << 16
    uint cells_hi;    // last cell (inclusive)
    uint key;         // object | kCellsKeySelf
    uint mode;        // kCellsEdges | kCellsPlane
    uint spare[3];    // to 96 bytes
};

// What the pair pass needs of a triangle: world vertices (the CPU's where the device has
// shaderFloat64, else as this GPU computed them), the bound on their difference from the
// CPU's (per coordinate) and the vertex indices; 64 bytes, four 16-byte words (written by
// packGeometry in cells_setup.glsl.inc).
struct CellsGeometry {
    float v[9];
    float eps;
    uint index[3];
    uint spare[3];
};

// One footprint: a triangle in a cell with its depth interval there.
struct CellsEntry {
    uint triangle;  // global triangle id
    uint key;       // object, self flag and box (kCellsBoxedObjects)
    float zlo, zhi;
};

// A pair of triangles whose intervals overlap in `cell` (a < b, global ids).
struct CellsCandidate {
    uint a, b, cell;
};

// A survivor's triangle of a download object, for the narrow phase (vkcollide::GpuTriangle,
// 52 bytes): global id, vertex indices within its object, world vertices computed as the
// CPU computes M * p (in double, rounded once) where the device has shaderFloat64, else the
// setup's float world vertices (within CellsGeometry::eps of the CPU's).
struct CellsGpuTriangle {
    uint id;
    uint vertex_index[3];
    float v[9];
};

// CellsCandidate.cell of a candidate the pair pass found outside its canonical cell, with
// proximity on (CellsParams.keep_neighbours): the proximity pass skips it without checking again.
VKC_CONST kCellsNotCanonical = 0xFFFFFFFFu;

// Small results; the host reads them after each run. The 64-bit counters count without
// wrapping whatever the scene: the host reads from them what a run needed.
struct CellsHeader {
    uint flags;             // kCells* above
    uint bad_triangle;      // smallest global triangle id with bad input (~0u: none)
    uint entries;           // footprints (needed entry capacity; at most box_cells when the scan ran)
    uint items;             // big-triangle work items (needed item capacity)
    uint survivors;         // pairs that passed (needed capacity)
    uint big_triangles;     // triangles handled in work items
    uint deep_cells;        // cells swept by the deep path
    uint deep_items;
    uint max_cell;          // most entries in one cell
    uint neighbours;        // overlapping pairs the sweep left out: one object, a shared vertex index
    uint duplicates;        // candidates dropped: not their canonical cell
    uint filtered;          // candidates the filter proved disjoint
    uint gpu_triangles;     // survivors' triangles of download objects (needed capacity)
    uint candidate_cells;   // cells where the sweep found at least one candidate
    uint64_t candidates;    // candidate pairs the sweep found (needed capacity)
    uint64_t box_cells;     // cells of the triangles' clamped footprint boxes, summed (setup)
    uint64_t comparisons;   // pairs of footprints sharing a cell, k (k - 1) / 2 summed over cells (scan)
    uint exact_tests;  // candidates the exact test decided (CellsParams.exact)
    uint exact_neighbours;  // of those, left out as neighbours: a bit-identical world vertex
    uint pairs_done;        // candidates the pair pass's chunks so far cover (CellsParams.pair_chunk)
    uint sweep_pending;     // 1: entries or deep items are left for the sweep's next chunk
    // Overlapping pairs the sweep dropped as repeats (not their canonical cell,
    // CellsParams.sweep_dedupe): with `candidates`, every overlapping pair the sweep found,
    // which the budget bounds.
    uint64_t repeats;
    // The sweep's current chunk (CellsParams.sweep_work): entries [begin, end) of the
    // shallow sweep and deep items [begin, end); each chunk starts where the last ended.
    uint sweep_entries_begin, sweep_entries_end;
    uint sweep_items_begin, sweep_items_end;
    uint sorted_need;       // entries CellsParams.sorted must hold: the end of the last huge cell
    uint huge_cells;        // cells of more than kCellsDeepShared entries (sorted in global memory)
    // Candidates of the current pair chunk the filter left for the exact pass
    // (CellsParams.exact_queue; cleared with each chunk's arguments).
    uint exact_queued;
    uint spare;
};

// Everything the shaders need, uploaded once per run (Push.frame points here).
struct CellsParams {
    VKC_ADDRESS(uint64_t) objects;       // ObjectGpu[object_count], sorted by triangle_base
    VKC_ADDRESS(uint64_t) object_flags;  // uint[object_count] (kCellsObjectSelf), or 0: none
    VKC_ADDRESS(uint64_t) pair_mask;     // bits [a * object_count + b], a < b: may collide; 0: all
    VKC_ADDRESS(uint64_t) projection;    // Projection
    VKC_ADDRESS(uint64_t) header;        // CellsHeader
    VKC_ADDRESS(uint64_t) triangles;     // CellsTriangle[triangle_count]
    VKC_ADDRESS(uint64_t) geometry;      // CellsGeometry[triangle_count]
    VKC_ADDRESS(uint64_t) counts;        // uint[cell_count]: footprints, then the fill cursor
    VKC_ADDRESS(uint64_t) offsets;       // uint[cell_count + 1]: first entry of each cell
    VKC_ADDRESS(uint64_t) block_sums;    // uint[block_count]
    VKC_ADDRESS(uint64_t) entries;       // CellsEntry[entry_capacity]
    VKC_ADDRESS(uint64_t) chunk_cells;   // uint[entry_capacity / kCellsEntryChunk + 1]: the cell of every
                                         // kCellsEntryChunk-th entry (the scan); the sweep searches from it
    VKC_ADDRESS(uint64_t) big_items;     // uvec2[item_capacity]: (triangle, chunk)
    VKC_ADDRESS(uint64_t) deep_items;    // uvec2[deep_capacity]: (cell, chunk or kCellsSorted)
    VKC_ADDRESS(uint64_t) candidates;    // CellsCandidate[candidate_capacity]
    VKC_ADDRESS(uint64_t) survivors;     // uvec2[survivor_capacity]: (a, b), a < b
    VKC_ADDRESS(uint64_t) args;          // uint[3 * kCellsArgsCount]
    VKC_ADDRESS(uint64_t) gpu_triangles; // CellsGpuTriangle[gpu_triangle_capacity] (host-visible), or 0: none
    VKC_ADDRESS(uint64_t) marks;         // uint[ceil(triangle_count / 32)]: downloaded already (cleared per run)
    // uvec2[sorted_capacity], indexed like `entries`, for huge cells only (cells_deep_sort.comp):
    // .x the cell's runs (the first sorted position of each object's entries, then k), .y
    // each sorted position's group end (one past its last coincident copy).
    VKC_ADDRESS(uint64_t) sorted;
    // uvec2[exact_queue_capacity]: with `exact`, the pair pass's candidates that the filter
    // did not prove disjoint, (a, b), for the exact pass (cells_exact.comp); 0 otherwise.
    VKC_ADDRESS(uint64_t) exact_queue;
    uint resolution;                     // N
    uint cell_count;                     // N * N
    uint object_count;
    uint triangle_count;
    uint entry_capacity;
    uint item_capacity;
    uint deep_capacity;
    uint candidate_capacity;
    uint survivor_capacity;
    uint block_count;                    // ceil(cell_count / kCellsScanBlock)
    uint max_groups_x;                   // maxComputeWorkGroupCount[0]
    uint use_filter;                     // 1: the double-precision filter runs
    uint gpu_triangle_capacity;
    uint budget;                         // kCellsOverBudget above; at most 2^31 - 1
    uint exact;  // 1: the pair pass decides exactly (needs use of the
        // double-precision pipeline); survivors then intersect
    // Proximity (src/proximity/): 1: the sweep keeps pairs of one object that share a vertex
    // index (their other primitives may be near) and the pair pass leaves them out of the
    // survivors instead.
    uint keep_neighbours;
    // Proximity: every triangle grown by this many world units along each axis (half the
    // distance, rounded up), so two triangles closer than the distance share a point.
    float proximity_pad;
    // Candidates the pair pass decides per submission: chunk k (the push constant's step)
    // covers [k * pair_chunk, (k + 1) * pair_chunk), so that no submission holds more
    // than about a target time of work (CellStage: the device's measured rate).
    uint pair_chunk;
    // Cells of at least this many entries drop a pair's repeats in the sweep (repeatsHere,
    // docs/reliable.md "Piles"; CellStage sets kCellsSweepDedupe).
    uint sweep_dedupe;
    // Work of one sweep chunk, in comparisons at most (an entry of the shallow sweep counts
    // as min(max_cell, kCellsSmallCell), a deep item as kCellsGroupSize * max_cell), so
    // that no submission holds more than about a target time of it (CellStage: the
    // device's measured rate); ~0u: the whole sweep in one chunk.
    uint sweep_work;
    uint sorted_capacity;  // elements of `sorted`
    // Loop iterations one invocation of the deep sweep or the huge cells' sort may run
    // (~0u: no limit). llvmpipe ends every loop of a shader invocation once their
    // iterations together pass 65,535, silently (gallivm's loop limiter); there the host sets
    // a bound below it, and a cell that needs more raises kCellsLoopLimit.
    uint loop_guard;
    uint exact_queue_capacity;  // as many as a pair chunk's candidates can be: it never overflows
};

// ---- Device pairs (DetectSettings::reliable.device_pairs; src/broad/cells/device_pairs.cpp) ---
// The survivors of an exact run, sorted on the GPU into the host result's order: bucketed
// by the lower triangle id (count, scan, scatter), each bucket sorted by the higher id with
// repeats dropped, a second scan, then written as DevicePair records.
// DevicePairsHeader.flags (vkcollide::kDevicePairs* in world.hpp, the same values):
VKC_CONST kDevicePairsOverflow = 1u;    // needed > capacity: the first `capacity` pairs written
VKC_CONST kDevicePairsLoopLimit = 4u;   // a bucket needs more loop iterations than CellsParams.loop_guard: failed
// kDevicePairsIncomplete: the run must be repeated or finished (a buffer overflowed, a mesh
// failed the GPU check, sweep or pair chunks are left: runComplete): count 0; collect() does it.
VKC_CONST kDevicePairsIncomplete = 2u;

// The public layout (vkcollide::DevicePairsHeader, TrianglePair).
struct DevicePairsHeader {
    uint count;              // pairs written: min(needed, capacity)
    uint needed;             // distinct intersecting pairs found
    uint flags;              // kDevicePairs*
    uint capacity;           // pairs the buffer holds
    uint responses;          // with device responses: responses written (every colliding triangle's)
    uint response_capacity;  // with device responses: responses the buffer holds (the run's triangles); else 0
    uint spare0, spare1;
};
struct DevicePair {
    uint object_a, triangle_a, object_b, triangle_b;
};

struct DevicePairsParams {
    VKC_ADDRESS(uint64_t) cells;         // CellsParams of the run (survivors, triangles, objects)
    VKC_ADDRESS(uint64_t) fault_header;  // the broad phase's Header (GPU input checks), or 0
    VKC_ADDRESS(uint64_t) object_ids;    // uint[object_count]: the id each object has in the result
    VKC_ADDRESS(uint64_t) counts;        // uint[triangle_count]: survivors per lower id, then the cursor, then distinct partners
    VKC_ADDRESS(uint64_t) offsets;       // uint[triangle_count + 1]: each lower id's first slot in partners
    VKC_ADDRESS(uint64_t) out_offsets;   // uint[triangle_count + 1]: its first output pair
    VKC_ADDRESS(uint64_t) block_sums;    // uint[block_count]
    VKC_ADDRESS(uint64_t) partners;      // uint[survivor capacity]: higher ids, bucketed by the lower
    VKC_ADDRESS(uint64_t) args;          // VkDispatchIndirectCommand: one invocation per survivor
    VKC_ADDRESS(uint64_t) header;        // DevicePairsHeader
    VKC_ADDRESS(uint64_t) pairs;         // DevicePair[capacity]
    uint triangle_count;
    uint block_count;                    // ceil(triangle_count / kCellsScanBlock)
    uint capacity;
    uint max_groups_x;
    uint response_capacity;  // with device responses: the run's triangles; else 0 (the header says it)
    // 1: the pairs go to the host only (its sorted result): `pairs` holds a uvec2 per pair,
    // its two global triangle ids (8 bytes, vkcollide::CandidatePair), half the DevicePair's
    // bytes to copy over the bus; the host names the objects. 0: DevicePair records (the
    // engine's).
    uint packed;
};
// Buckets up to this size are sorted by insertion, larger ones by heap sort (in place).
VKC_CONST kDevicePairsInsertionSort = 16u;

// ---- Device responses (DetectSettings::reliable.device_responses; src/broad/cells/device_responses.cpp) ---
// Every colliding triangle's response (vkcollide::TriangleResponse) from the device pairs'
// sorted buckets: each triangle's lower partners bucketed and sorted the same way (count,
// scan, scatter, sort), the unit normals, then the terms summed in ascending partner order
// (the CPU's order) with correctly rounded division and square root (rounded_fp64.glsl.inc).
struct DeviceResponse {
    uint object, triangle;
    uint direction[3];  // float bits (rounded from double through the bits: no flush)
    uint partner_count;
};
struct DeviceResponsesParams {
    VKC_ADDRESS(uint64_t) pairs;         // DevicePairsParams of the same run (buckets, header, object ids)
    VKC_ADDRESS(uint64_t) lower_counts;  // uint[triangle_count]: pairs where the triangle is the higher end, then the cursor
    VKC_ADDRESS(uint64_t) lower_offsets; // uint[triangle_count + 1]: its first slot in `lower`
    VKC_ADDRESS(uint64_t) lower;         // uint[survivor capacity]: lower partners, bucketed by the higher
    VKC_ADDRESS(uint64_t) marks;         // uint[triangle_count]: 1 where the triangle is in a pair
    VKC_ADDRESS(uint64_t) positions;     // uint[triangle_count + 1]: its response's index
    VKC_ADDRESS(uint64_t) responders;    // uint[triangle_count]: the marked triangles in order (positions' inverse)
    VKC_ADDRESS(uint64_t) args;          // VkDispatchIndirectCommand: one invocation per responder
    VKC_ADDRESS(uint64_t) normals;       // double[3 * triangle_count]: unit normals of marked triangles
    VKC_ADDRESS(uint64_t) responses;     // DeviceResponse[triangle_count]
    uint triangle_count;
    uint block_count;  // ceil(triangle_count / kCellsScanBlock)
    uint max_groups_x;
    uint spare;
};

// ---- Few pairs sorted in one pass (PairSort::Auto below kGpuPairSortFrom; src/broad/cells/small_sort.cpp) ---
// One workgroup sorts the exact run's survivors (global ids a < b, unsorted, a rare pair
// twice) into the host result's order and drops repeats (a bitonic sort in shared memory),
// orders the pairs' ends by merging two sorted lists and lists the responders; then one
// invocation per responder computes every colliding triangle's response (as DeviceResponse,
// to the bit the CPU's). Where the survivors do not fit (or the run is incomplete) it writes
// kSmallSortSkipped and the host sorts them as before. spirv/cells/small_sort.comp.glsl and
// small_sort_respond.comp.glsl have the steps.
VKC_CONST kSmallSortGroupSize = 1024u;
VKC_CONST kSmallSortPairs = 4096u;  // survivors it sorts: its shared memory holds 8 bytes each (32 KiB)
VKC_CONST kSmallSortDone = 1u;
VKC_CONST kSmallSortSkipped = 2u;   // too many survivors, an incomplete run, or a survivor out of range
struct SmallSortHeader {
    uint status;     // kSmallSort*
    uint survivors;  // the run's survivors (repeats included)
    uint pairs;      // distinct pairs, sorted, in `pairs`
    uint responses;  // responses, in triangle order, in `responses`
};
struct SmallSortParams {
    VKC_ADDRESS(uint64_t) cells;      // CellsParams of the run (survivors, triangles, geometry, objects)
    VKC_ADDRESS(uint64_t) header;     // SmallSortHeader
    VKC_ADDRESS(uint64_t) pairs;      // uvec2[kSmallSortPairs]: the distinct pairs (a, b), ascending
    VKC_ADDRESS(uint64_t) ends;       // uvec2[2 kSmallSortPairs]: each pair's two ends (triangle, partner), ascending
    VKC_ADDRESS(uint64_t) responders;  // uint[2 kSmallSortPairs]: each responder's triangle (global id), ascending
    VKC_ADDRESS(uint64_t) run_begin;   // uint[2 kSmallSortPairs + 1]: each responder's first end; then the end count
    VKC_ADDRESS(uint64_t) args;        // VkDispatchIndirectCommand: small_sort_respond.comp over the responders
    VKC_ADDRESS(uint64_t) normals;     // double[3 * 2 kSmallSortPairs]: each responder's unit normal
    VKC_ADDRESS(uint64_t) responses;   // DeviceResponse[2 kSmallSortPairs]
    uint triangle_count;
    uint spare;
};

// Unit test of the filter alone (tests/shaders/cells_filter_test.comp): one pair per invocation.
struct CellsFilterCase {
    float a[9];
    float b[9];
    float eps_a, eps_b;
};
struct CellsFilterParams {
    VKC_ADDRESS(uint64_t) cases;    // CellsFilterCase[count]
    VKC_ADDRESS(uint64_t) verdict;  // uint[count]: 1 rejected (proved disjoint), 0 kept
    uint count;
    uint pad;
};

#ifdef __cplusplus
}  // namespace vkcollide::gpu
#endif
#endif
