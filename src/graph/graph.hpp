// Render graph, host side: passes declare the resources they use and how; compile()
// orders them, culls dead passes and derives every barrier and image layout transition
// (synchronization2 terms). Nothing here touches a device, so it is unit-tested on the host.
// The executor (graph/executor.hpp) allocates transients, records and submits the plan.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <vulkan/vulkan_core.h>

#include "vkcollide/result.hpp"

namespace vkcollide::vk {
class Buffer;
class Image;
}  // namespace vkcollide::vk

namespace vkcollide::graph {

enum class PassKind : std::uint8_t { Raster, Compute, Transfer };

// How a pass uses a resource. Shader uses take their stage from the pass kind: vertex +
// fragment for raster passes, compute for compute passes.
enum class Use : std::uint8_t {
    ColorAttachment,   // image, written through dynamic rendering
    DepthAttachment,   // image, depth test and write
    Sampled,           // image, read through a sampler
    StorageRead,       // image or buffer
    StorageWrite,      // image or buffer
    StorageReadWrite,  // image or buffer (atomics)
    IndirectRead,      // buffer: indirect draw/dispatch arguments
    TransferSrc,       // image or buffer
    TransferDst,       // image or buffer (fills, clears, copies)
};

const char* toString(Use use) noexcept;
bool isWrite(Use use) noexcept;

struct ResourceId {
    std::uint32_t index = ~0u;
    bool valid() const noexcept { return index != ~0u; }
    friend bool operator==(ResourceId, ResourceId) = default;
};

struct ImageInfo {
    VkFormat format = VK_FORMAT_UNDEFINED;
    std::uint32_t width = 0, height = 0, mip_levels = 1;
};

struct ResourceDecl {
    std::string name;
    bool is_image = false;
    bool imported = false;      // lives outside the graph; its contents matter after execution
    bool host_readback = false; // the host reads it after execution (buffer)
    ImageInfo image;
    VkDeviceSize size = 0;      // buffers
    VkImageLayout initial_layout = VK_IMAGE_LAYOUT_UNDEFINED;  // imported images
    VkImageLayout final_layout = VK_IMAGE_LAYOUT_UNDEFINED;    // imported images; UNDEFINED: leave as is
    vk::Buffer* external_buffer = nullptr;
    vk::Image* external_image = nullptr;
};

struct Access {
    ResourceId resource;
    Use use = Use::StorageRead;
    std::uint32_t base_mip = 0;
    std::uint32_t mip_count = VK_REMAINING_MIP_LEVELS;
    VkAttachmentLoadOp load_op = VK_ATTACHMENT_LOAD_OP_LOAD;  // attachments
    VkClearValue clear{};
};

class PassContext;  // graph/pass_context.hpp: resources and recording calls, onto the executor's tape
using RecordFn = std::function<void(PassContext&)>;

// What a pass belongs to, in the terms of the code that builds the graph (the broad phase
// casts its Stage enum); reported with the pass's GPU time. The graph never reads it.
using StageTag = std::uint8_t;

struct PassDecl {
    std::string name;
    PassKind kind = PassKind::Compute;
    std::vector<Access> accesses;
    std::uint32_t render_width = 0, render_height = 0;  // raster: defaults to the attachments' size
    bool side_effects = false;  // never culled (e.g. writes only memory the graph does not track)
    StageTag stage = 0;         // 0: none given
    RecordFn record;
};

class Graph;

// Fluent declaration of one pass's uses; returned by Graph::addPass.
class PassBuilder {
public:
    PassBuilder(Graph& graph, std::uint32_t pass) : graph_(&graph), pass_(pass) {}
    PassBuilder& use(ResourceId r, Use use, std::uint32_t base_mip = 0, std::uint32_t mip_count = VK_REMAINING_MIP_LEVELS);
    PassBuilder& read(ResourceId r) { return use(r, Use::StorageRead); }
    PassBuilder& write(ResourceId r) { return use(r, Use::StorageWrite); }
    PassBuilder& readWrite(ResourceId r) { return use(r, Use::StorageReadWrite); }
    PassBuilder& sampled(ResourceId r) { return use(r, Use::Sampled); }
    PassBuilder& indirect(ResourceId r) { return use(r, Use::IndirectRead); }
    PassBuilder& colorAttachment(ResourceId r, VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR, VkClearValue clear = {});
    PassBuilder& depthAttachment(ResourceId r, VkAttachmentLoadOp load = VK_ATTACHMENT_LOAD_OP_CLEAR, float clear_depth = 1.0f);
    PassBuilder& renderArea(std::uint32_t width, std::uint32_t height);
    PassBuilder& sideEffects();
    PassBuilder& stage(StageTag tag);
    PassBuilder& record(RecordFn fn);
    std::uint32_t index() const noexcept { return pass_; }

private:
    Graph* graph_;
    std::uint32_t pass_;
};

// One derived barrier. For images, `layout_old/new` and a mip range apply.
struct Barrier {
    ResourceId resource;
    bool is_image = false;
    VkPipelineStageFlags2 src_stage = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 src_access = VK_ACCESS_2_NONE;
    VkPipelineStageFlags2 dst_stage = VK_PIPELINE_STAGE_2_NONE;
    VkAccessFlags2 dst_access = VK_ACCESS_2_NONE;
    VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImageLayout new_layout = VK_IMAGE_LAYOUT_UNDEFINED;
    std::uint32_t base_mip = 0, mip_count = 1;
};

struct PlannedPass {
    std::uint32_t pass = 0;         // index into Graph::passes()
    std::vector<Barrier> barriers;  // recorded before the pass
};

struct GraphPlan {
    std::vector<PlannedPass> order;     // execution order, culled passes removed
    std::vector<std::uint32_t> culled;  // passes whose results nobody uses
    std::vector<Barrier> final_barriers;  // host readback, final layouts of imported images
    // Union of the uses of each resource, to create transients with the right usage.
    std::vector<VkImageUsageFlags> image_usage;
    std::vector<VkBufferUsageFlags> buffer_usage;
    // First and last position in `order` that touches each resource (~0u if none).
    std::vector<std::pair<std::uint32_t, std::uint32_t>> lifetime;
};

class Graph {
public:
    ResourceId createBuffer(std::string name, VkDeviceSize size);
    ResourceId createImage(std::string name, const ImageInfo& info);
    // External resources: their contents survive execution, so passes writing them are live.
    ResourceId importBuffer(std::string name, vk::Buffer& buffer, bool host_readback = false);
    ResourceId importBuffer(std::string name, VkDeviceSize size, bool host_readback = false);  // planning only
    ResourceId importImage(std::string name, vk::Image* image, const ImageInfo& info, VkImageLayout initial,
                           VkImageLayout final_layout);

    PassBuilder addPass(std::string name, PassKind kind);
    // A pass repeated `count` times, e.g. one per depth-peeling layer; `declare` gets the
    // iteration index and typically swaps ping-pong resources on its parity.
    void repeatPass(const std::string& name, PassKind kind, std::uint32_t count,
                    const std::function<void(PassBuilder&, std::uint32_t)>& declare);

    // Checks every declaration and derives the plan. Phases are commented in the .cpp.
    [[nodiscard]] Result<GraphPlan> compile() const;
    // Everything compile() reads, flattened into `out` (its capacity reused): graphs with
    // equal keys compile to equal plans, so an executor may reuse the last plan (the
    // declarations of a detection repeat frame after frame). Not in it, because compile()
    // never reads them: names, buffer sizes, image formats and extents, clear values,
    // external resources and what the record callbacks capture.
    void planKey(std::vector<std::uint64_t>& out) const;

    const std::vector<ResourceDecl>& resources() const noexcept { return resources_; }
    const std::vector<PassDecl>& passes() const noexcept { return passes_; }
    const ResourceDecl& resource(ResourceId id) const { return resources_.at(id.index); }

private:
    friend class PassBuilder;
    ResourceId add(ResourceDecl decl);
    std::vector<ResourceDecl> resources_;
    std::vector<PassDecl> passes_;
};

}  // namespace vkcollide::graph
