// Graph::compile(): checks the declarations, finds the dependencies, culls dead passes,
// orders the rest and derives their barriers and layout transitions; planKey() names
// everything compile() reads.
#include "graph/graph.hpp"

#include <algorithm>
#include <functional>
#include <queue>
#include <string>
#include <vector>

#include "graph/use_info.hpp"

namespace vkcollide::graph {
namespace {

// Synchronization state of one buffer or one image mip level.
struct SubresourceState {
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 write_stages = VK_PIPELINE_STAGE_2_NONE;  // last writer (or layout transition)
    VkAccessFlags2 write_access = VK_ACCESS_2_NONE;                 // what it wrote
    VkPipelineStageFlags2 read_stages = VK_PIPELINE_STAGE_2_NONE;   // readers since that write
    VkPipelineStageFlags2 visible_stages = VK_PIPELINE_STAGE_2_NONE;  // stages the write is visible to
    VkAccessFlags2 visible_access = VK_ACCESS_2_NONE;
};

// Applies one access to a subresource's state; returns a barrier if one is needed.
bool transition(SubresourceState& s, const UseInfo& u, bool is_image, Barrier& out) {
    const bool layout_change = is_image && s.layout != u.layout;
    const bool had_access = s.write_stages != VK_PIPELINE_STAGE_2_NONE || s.read_stages != VK_PIPELINE_STAGE_2_NONE;
    out.old_layout = s.layout;
    out.new_layout = is_image ? u.layout : VK_IMAGE_LAYOUT_UNDEFINED;
    out.dst_stage = u.stage;
    out.dst_access = u.access;
    if (u.write || layout_change) {
        // Write-after-write/read, or a layout transition: wait for every earlier access,
        // flush the last write.
        if (!had_access && !layout_change) {
            s.write_stages = u.stage;
            s.write_access = u.write ? u.access : VK_ACCESS_2_NONE;
            s.read_stages = u.write ? VK_PIPELINE_STAGE_2_NONE : u.stage;
            s.visible_stages = VK_PIPELINE_STAGE_2_NONE;
            s.visible_access = VK_ACCESS_2_NONE;
            return false;
        }
        out.src_stage = s.write_stages | s.read_stages;
        out.src_access = s.write_access;
        s.layout = out.new_layout;
        if (u.write) {
            s.write_stages = u.stage;
            s.write_access = u.access;
            s.read_stages = VK_PIPELINE_STAGE_2_NONE;
            s.visible_stages = VK_PIPELINE_STAGE_2_NONE;
            s.visible_access = VK_ACCESS_2_NONE;
        } else {
            // A transition for reading acts as a write that is already visible to u.stage.
            s.write_stages |= u.stage;
            s.read_stages = u.stage;
            s.visible_stages = u.stage;
            s.visible_access = u.access;
        }
        return true;
    }
    // Read: needs a barrier only if an unflushed write is not yet visible to this stage/access.
    s.read_stages |= u.stage;
    if (s.write_stages == VK_PIPELINE_STAGE_2_NONE) return false;
    if ((s.visible_stages & u.stage) == u.stage && (s.visible_access & u.access) == u.access) return false;
    out.src_stage = s.write_stages;
    out.src_access = s.write_access;
    s.visible_stages |= u.stage;
    s.visible_access |= u.access;
    return true;
}

}  // namespace

// Keep in step with compile(): every field it reads is here (tests/graph/graph_plan_tests.cpp
// changes each one and expects a different key).
void Graph::planKey(std::vector<std::uint64_t>& out) const {
    using U = std::uint64_t;
    out.clear();
    out.push_back(U(resources_.size()) | U(passes_.size()) << 32);
    for (const ResourceDecl& r : resources_) {
        out.push_back(U(r.is_image) | U(r.imported) << 1 | U(r.host_readback) << 2 | U(r.image.mip_levels) << 32);
        out.push_back(U(std::uint32_t(r.initial_layout)) | U(std::uint32_t(r.final_layout)) << 32);
    }
    for (const PassDecl& p : passes_) {
        out.push_back(U(p.kind) | U(p.side_effects) << 8 | U(static_cast<bool>(p.record)) << 9 | U(p.accesses.size()) << 32);
        out.push_back(U(p.render_width) | U(p.render_height) << 32);
        for (const Access& a : p.accesses) {
            out.push_back(U(a.resource.index) | U(a.use) << 32);
            out.push_back(U(a.base_mip) | U(a.mip_count) << 32);
            out.push_back(U(std::uint32_t(a.load_op)));
        }
    }
}

Result<GraphPlan> Graph::compile() const {
    const auto n_res = static_cast<std::uint32_t>(resources_.size());
    const auto n_pass = static_cast<std::uint32_t>(passes_.size());
    auto fail = [](const std::string& what) { return Error(ErrorCode::GraphError, what); };

    // Phase 1: validate each declaration on its own.
    for (const PassDecl& p : passes_) {
        const std::string where = "pass '" + p.name + "': ";
        bool has_attachment = false;
        for (const Access& a : p.accesses) {
            if (!a.resource.valid() || a.resource.index >= n_res) return fail(where + "uses an undeclared resource");
            const ResourceDecl& r = resources_[a.resource.index];
            const bool image_only = a.use == Use::ColorAttachment || a.use == Use::DepthAttachment || a.use == Use::Sampled;
            if (image_only && !r.is_image) return fail(where + "uses buffer '" + r.name + "' as " + toString(a.use));
            if (a.use == Use::IndirectRead && r.is_image) return fail(where + "uses image '" + r.name + "' as indirect arguments");
            if (a.use == Use::ColorAttachment || a.use == Use::DepthAttachment) {
                has_attachment = true;
                if (p.kind != PassKind::Raster) return fail(where + "a " + std::string(p.kind == PassKind::Compute ? "compute" : "transfer") +
                                                            " pass cannot use '" + r.name + "' as an attachment");
            }
            if ((p.kind == PassKind::Transfer) != (a.use == Use::TransferSrc || a.use == Use::TransferDst))
                return fail(where + "uses '" + r.name + "' as " + toString(a.use) + ", which its pass kind cannot do");
            if (r.is_image) {
                std::uint32_t count = a.mip_count == VK_REMAINING_MIP_LEVELS ? r.image.mip_levels - a.base_mip : a.mip_count;
                if (a.base_mip >= r.image.mip_levels || a.base_mip + count > r.image.mip_levels || count == 0)
                    return fail(where + "mip range of '" + r.name + "' is outside its " + std::to_string(r.image.mip_levels) + " levels");
            }
        }
        for (std::size_t i = 0; i < p.accesses.size(); ++i)
            for (std::size_t j = i + 1; j < p.accesses.size(); ++j) {
                const Access &a = p.accesses[i], &b = p.accesses[j];
                if (a.resource != b.resource) continue;
                const ResourceDecl& r = resources_[a.resource.index];
                const bool overlap = !r.is_image || !(a.base_mip + (a.mip_count == VK_REMAINING_MIP_LEVELS ? r.image.mip_levels : a.mip_count) <= b.base_mip ||
                                                      b.base_mip + (b.mip_count == VK_REMAINING_MIP_LEVELS ? r.image.mip_levels : b.mip_count) <= a.base_mip);
                if (overlap) return fail(where + "declares '" + r.name + "' twice; declare one combined use (e.g. storage read-write)");
            }
        if (p.kind == PassKind::Raster && !has_attachment && (p.render_width == 0 || p.render_height == 0))
            return fail(where + "a raster pass without attachments needs renderArea()");
        if (!p.record) return fail(where + "has no record callback");
    }

    // Phase 2: dependencies. Declaration order is submission intent: a read depends on the
    // latest earlier writer, a write on the latest writer and every reader since (WAR).
    std::vector<std::vector<std::uint32_t>> deps(n_pass);
    {
        std::vector<std::int64_t> last_writer(n_res, -1);
        std::vector<std::vector<std::uint32_t>> readers(n_res);
        for (std::uint32_t pi = 0; pi < n_pass; ++pi) {
            for (const Access& a : passes_[pi].accesses) {
                const std::uint32_t r = a.resource.index;
                const bool w = isWrite(a.use);
                const bool loads = a.use == Use::StorageReadWrite || !w ||
                                   ((a.use == Use::ColorAttachment || a.use == Use::DepthAttachment) && a.load_op == VK_ATTACHMENT_LOAD_OP_LOAD);
                if (loads && last_writer[r] < 0 && !resources_[r].imported)
                    return fail("pass '" + passes_[pi].name + "' reads '" + resources_[r].name + "' before any pass writes it");
                if (last_writer[r] >= 0) deps[pi].push_back(static_cast<std::uint32_t>(last_writer[r]));
                if (w) {
                    for (std::uint32_t rd : readers[r])
                        if (rd != pi) deps[pi].push_back(rd);
                    readers[r].clear();
                }
            }
            for (const Access& a : passes_[pi].accesses) {
                if (isWrite(a.use)) last_writer[a.resource.index] = pi;
                else readers[a.resource.index].push_back(pi);
            }
        }
    }

    // Phase 3: cull passes whose results nobody uses: live roots write an imported
    // resource or declare side effects; liveness flows back along dependencies.
    std::vector<bool> live(n_pass, false);
    for (std::int64_t pi = n_pass - 1; pi >= 0; --pi) {
        const PassDecl& p = passes_[static_cast<std::size_t>(pi)];
        bool root = p.side_effects;
        for (const Access& a : p.accesses)
            if (isWrite(a.use) && resources_[a.resource.index].imported) root = true;
        if (root) live[static_cast<std::size_t>(pi)] = true;
    }
    for (std::int64_t pi = n_pass - 1; pi >= 0; --pi)
        if (live[static_cast<std::size_t>(pi)])
            for (std::uint32_t d : deps[static_cast<std::size_t>(pi)]) live[d] = true;

    // Phase 4: order the live passes topologically, declaration order breaking ties, so a
    // graph declared in a valid order runs as declared.
    GraphPlan plan;
    {
        std::vector<std::uint32_t> indegree(n_pass, 0);
        std::vector<std::vector<std::uint32_t>> users(n_pass);
        for (std::uint32_t pi = 0; pi < n_pass; ++pi) {
            if (!live[pi]) continue;
            std::vector<std::uint32_t> unique = deps[pi];
            std::sort(unique.begin(), unique.end());
            unique.erase(std::unique(unique.begin(), unique.end()), unique.end());
            for (std::uint32_t d : unique) {
                ++indegree[pi];
                users[d].push_back(pi);
            }
        }
        std::priority_queue<std::uint32_t, std::vector<std::uint32_t>, std::greater<>> ready;
        for (std::uint32_t pi = 0; pi < n_pass; ++pi)
            if (live[pi] && indegree[pi] == 0) ready.push(pi);
            else if (!live[pi]) plan.culled.push_back(pi);
        while (!ready.empty()) {
            std::uint32_t pi = ready.top();
            ready.pop();
            plan.order.push_back({pi, {}});
            for (std::uint32_t u : users[pi])
                if (--indegree[u] == 0) ready.push(u);
        }
    }

    // Phase 5: walk the order, tracking each buffer and image mip level, and derive the
    // barriers and layout transitions; collect usage flags and lifetimes.
    plan.image_usage.assign(n_res, 0);
    plan.buffer_usage.assign(n_res, 0);
    plan.lifetime.assign(n_res, {~0u, ~0u});
    std::vector<std::vector<SubresourceState>> state(n_res);
    for (std::uint32_t r = 0; r < n_res; ++r) {
        const ResourceDecl& d = resources_[r];
        state[r].resize(d.is_image ? d.image.mip_levels : 1);
        for (auto& s : state[r]) s.layout = d.is_image ? d.initial_layout : VK_IMAGE_LAYOUT_UNDEFINED;
        if (d.imported) {
            // Imported contents were written before this graph: wait for all of it.
            for (auto& s : state[r]) {
                s.write_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
                s.write_access = VK_ACCESS_2_MEMORY_WRITE_BIT;
            }
        }
    }
    for (std::uint32_t oi = 0; oi < plan.order.size(); ++oi) {
        PlannedPass& planned = plan.order[oi];
        const PassDecl& p = passes_[planned.pass];
        for (const Access& a : p.accesses) {
            const std::uint32_t r = a.resource.index;
            const ResourceDecl& d = resources_[r];
            const UseInfo u = describe(a.use, p.kind);
            if (d.is_image) plan.image_usage[r] |= u.image_usage;
            else plan.buffer_usage[r] |= u.buffer_usage;
            auto& life = plan.lifetime[r];
            if (life.first == ~0u) life.first = oi;
            life.second = oi;
            const std::uint32_t count = d.is_image ? (a.mip_count == VK_REMAINING_MIP_LEVELS ? d.image.mip_levels - a.base_mip : a.mip_count) : 1;
            for (std::uint32_t m = a.base_mip; m < a.base_mip + count; ++m) {
                Barrier b;
                b.resource = a.resource;
                b.is_image = d.is_image;
                b.base_mip = m;
                b.mip_count = 1;
                if (!transition(state[r][m], u, d.is_image, b)) continue;
                // Merge with the previous level's barrier when identical (one barrier per range).
                if (!planned.barriers.empty()) {
                    Barrier& prev = planned.barriers.back();
                    if (prev.resource == b.resource && prev.base_mip + prev.mip_count == m && prev.src_stage == b.src_stage &&
                        prev.src_access == b.src_access && prev.dst_stage == b.dst_stage && prev.dst_access == b.dst_access &&
                        prev.old_layout == b.old_layout && prev.new_layout == b.new_layout) {
                        ++prev.mip_count;
                        continue;
                    }
                }
                planned.barriers.push_back(b);
            }
        }
    }

    // Phase 6: final barriers: host readback buffers and imported images' final layouts.
    for (std::uint32_t r = 0; r < n_res; ++r) {
        const ResourceDecl& d = resources_[r];
        if (d.host_readback && !d.is_image) {
            SubresourceState& s = state[r][0];
            if (s.write_access != VK_ACCESS_2_NONE && s.write_stages != VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT) {
                Barrier b;
                b.resource = ResourceId{r};
                b.src_stage = s.write_stages;
                b.src_access = s.write_access;
                b.dst_stage = VK_PIPELINE_STAGE_2_HOST_BIT;
                b.dst_access = VK_ACCESS_2_HOST_READ_BIT;
                plan.final_barriers.push_back(b);
            }
        }
        if (d.is_image && d.imported && d.final_layout != VK_IMAGE_LAYOUT_UNDEFINED) {
            for (std::uint32_t m = 0; m < d.image.mip_levels; ++m) {
                SubresourceState& s = state[r][m];
                if (s.layout == d.final_layout) continue;
                Barrier b;
                b.resource = ResourceId{r};
                b.is_image = true;
                b.base_mip = m;
                b.src_stage = s.write_stages | s.read_stages;
                b.src_access = s.write_access;
                b.dst_stage = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
                b.dst_access = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
                b.old_layout = s.layout;
                b.new_layout = d.final_layout;
                plan.final_barriers.push_back(b);
            }
        }
    }
    return plan;
}

}  // namespace vkcollide::graph
