// Paper pass 4, packing: the triangles separation kept, compacted in global triangle order
// into the host-visible records buffer (CandidateTriangle), with the count in the header.
// Two methods, identical records:
//   PackingMethod::Paper: the sparse array seen as a texture of kPackRowWidth columns;
//     "pack-count" (non-empty texels per row, then their prefix sum), "pack-shift" (each
//     row's survivors shifted to its end), "pack-move" (one workgroup per row writes them);
//   PackingMethod::Scan: "pack-scan" (survivors per block and their prefix sum), then
//     "pack-scatter" (each survivor writes its record).
#pragma once

#include <memory>

#include "broad/dispatch.hpp"
#include "broad/run_view.hpp"
#include "broad/stage.hpp"

namespace vkcollide::passes {

class Packing {
public:
    static Result<std::unique_ptr<Packing>> create(vk::Device& device);

    struct Buffers {
        graph::ResourceId sparse, scratch, header, projection, records;
        graph::ResourceId sparse_depth;  // kept depth ranges (depth-aware separation), else invalid
    };
    void record(graph::Graph& g, const RunView& run, const Buffers& b) const;
    // Scratch bytes for `triangles` (both methods).
    static VkDeviceSize scratchBytes(std::uint32_t triangles);

private:
    Packing() = default;
    vk::Pipeline pack_rowcount_, scan_counts_, pack_shift_, pack_move_, scan_blocksum_, scan_scatter_;
};

}  // namespace vkcollide::passes
