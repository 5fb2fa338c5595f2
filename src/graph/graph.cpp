// Declaring a graph: its resources and its passes with their uses (PassBuilder). What
// compile() makes of them is in graph/compile.cpp, what each use means in graph/use_info.cpp.
#include "graph/graph.hpp"

#include <functional>
#include <string>
#include <utility>

namespace vkcollide::graph {

PassBuilder& PassBuilder::use(ResourceId r, Use u, std::uint32_t base_mip, std::uint32_t mip_count) {
    Access a;
    a.resource = r;
    a.use = u;
    a.base_mip = base_mip;
    a.mip_count = mip_count;
    graph_->passes_[pass_].accesses.push_back(a);
    return *this;
}

PassBuilder& PassBuilder::colorAttachment(ResourceId r, VkAttachmentLoadOp load, VkClearValue clear) {
    use(r, Use::ColorAttachment, 0, 1);
    graph_->passes_[pass_].accesses.back().load_op = load;
    graph_->passes_[pass_].accesses.back().clear = clear;
    return *this;
}

PassBuilder& PassBuilder::depthAttachment(ResourceId r, VkAttachmentLoadOp load, float clear_depth) {
    use(r, Use::DepthAttachment, 0, 1);
    graph_->passes_[pass_].accesses.back().load_op = load;
    graph_->passes_[pass_].accesses.back().clear.depthStencil = {clear_depth, 0};
    return *this;
}

PassBuilder& PassBuilder::renderArea(std::uint32_t width, std::uint32_t height) {
    graph_->passes_[pass_].render_width = width;
    graph_->passes_[pass_].render_height = height;
    return *this;
}

PassBuilder& PassBuilder::sideEffects() {
    graph_->passes_[pass_].side_effects = true;
    return *this;
}

PassBuilder& PassBuilder::stage(StageTag tag) {
    graph_->passes_[pass_].stage = tag;
    return *this;
}

PassBuilder& PassBuilder::record(RecordFn fn) {
    graph_->passes_[pass_].record = std::move(fn);
    return *this;
}

ResourceId Graph::add(ResourceDecl decl) {
    resources_.push_back(std::move(decl));
    return ResourceId{static_cast<std::uint32_t>(resources_.size() - 1)};
}

ResourceId Graph::createBuffer(std::string name, VkDeviceSize size) {
    ResourceDecl d;
    d.name = std::move(name);
    d.size = size;
    return add(std::move(d));
}

ResourceId Graph::createImage(std::string name, const ImageInfo& info) {
    ResourceDecl d;
    d.name = std::move(name);
    d.is_image = true;
    d.image = info;
    return add(std::move(d));
}

ResourceId Graph::importBuffer(std::string name, VkDeviceSize size, bool host_readback) {
    ResourceDecl d;
    d.name = std::move(name);
    d.size = size;
    d.imported = true;
    d.host_readback = host_readback;
    return add(std::move(d));
}

ResourceId Graph::importImage(std::string name, vk::Image* image, const ImageInfo& info, VkImageLayout initial,
                              VkImageLayout final_layout) {
    ResourceDecl d;
    d.name = std::move(name);
    d.is_image = true;
    d.imported = true;
    d.image = info;
    d.external_image = image;
    d.initial_layout = initial;
    d.final_layout = final_layout;
    return add(std::move(d));
}

PassBuilder Graph::addPass(std::string name, PassKind kind) {
    PassDecl p;
    p.name = std::move(name);
    p.kind = kind;
    passes_.push_back(std::move(p));
    return PassBuilder(*this, static_cast<std::uint32_t>(passes_.size() - 1));
}

void Graph::repeatPass(const std::string& name, PassKind kind, std::uint32_t count,
                       const std::function<void(PassBuilder&, std::uint32_t)>& declare) {
    for (std::uint32_t i = 0; i < count; ++i) {
        PassBuilder b = addPass(name + "[" + std::to_string(i) + "]", kind);
        declare(b, i);
    }
}

}  // namespace vkcollide::graph
