#include "graph/executor.hpp"

#include <algorithm>
#include <utility>

#include "vk/debug_names.hpp"

namespace vkcollide::graph {

std::uint64_t waitNs(std::uint64_t timeout_ns, const std::optional<std::chrono::steady_clock::time_point>& deadline) {
    if (!deadline) return timeout_ns;
    const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(*deadline - std::chrono::steady_clock::now()).count();
    return left > 0 ? static_cast<std::uint64_t>(left) : 0;
}

Error timeoutOfDetection(std::uint64_t timeout_ns, bool has_deadline, Error e) {
    if (e.code() != ErrorCode::Timeout || !has_deadline) return e;
    return Error(ErrorCode::Timeout,
                 "the detection's GPU work did not finish within " + std::to_string(timeout_ns / 1000000) +
                     " ms (its timeout, DetectSettings::limits.timeout_ms, for every submission and rerun together)",
                 e.vkResult());
}

HostTimes& HostTimes::operator+=(const HostTimes& o) noexcept {
    upload_ms += o.upload_ms;
    declare_ms += o.declare_ms;
    compile_ms += o.compile_ms;
    record_ms += o.record_ms;
    submit_ms += o.submit_ms;
    wait_ms += o.wait_ms;
    milestone_ms += o.milestone_ms;
    gpu_span_ms += o.gpu_span_ms;
    launch_wake_ms += o.launch_wake_ms;
    submissions += o.submissions;
    reused += o.reused;
    return *this;
}

namespace {

using Clock = std::chrono::steady_clock;

double msBetween(Clock::time_point t0, Clock::time_point t1) { return std::chrono::duration<double, std::milli>(t1 - t0).count(); }

Error timeoutError(std::uint64_t timeout_ns) {
    return Error(ErrorCode::Timeout, "GPU work did not finish within " + std::to_string(timeout_ns / 1000000) + " ms", VK_TIMEOUT);
}

// The submission's wait, with a timeout reported as ErrorCode::Timeout.
Result<void> waitFor(vk::Submission& s, std::uint64_t timeout_ns) {
    auto ok = s.wait(timeout_ns);
    if (!ok && ok.error().vkResult() == VK_TIMEOUT) return timeoutError(timeout_ns);
    return ok;
}

}  // namespace

Executor::~Executor() {
    submission_.reset();  // waits for work in flight before anything is freed
    if (queries_) device_->fns.vkDestroyQueryPool(device_->device, queries_, device_->allocator());
}

Result<void> Executor::prepareResources(const Graph& graph, const GraphPlan& plan, PassContext& ctx) {
    const auto& res = graph.resources();
    ctx.buffers_.assign(res.size(), nullptr);
    ctx.images_.assign(res.size(), nullptr);
    for (std::uint32_t r = 0; r < res.size(); ++r) {
        const ResourceDecl& d = res[r];
        if (plan.lifetime[r].first == ~0u && !d.imported) continue;  // unused transient
        if (d.imported) {
            if (d.is_image) {
                if (!d.external_image) return Error(ErrorCode::GraphError, "imported image '" + d.name + "' has no image");
                ctx.images_[r] = d.external_image;
            } else {
                if (!d.external_buffer) return Error(ErrorCode::GraphError, "imported buffer '" + d.name + "' has no buffer (planning-only import)");
                ctx.buffers_[r] = d.external_buffer;
            }
            continue;
        }
        if (d.is_image) {
            CachedImage& c = images_[d.name];
            const VkImageUsageFlags usage = plan.image_usage[r];
            if (!c.image.valid() || c.usage != usage || c.info.format != d.image.format || c.info.width != d.image.width ||
                c.info.height != d.image.height || c.info.mip_levels != d.image.mip_levels) {
                vk::ImageDesc desc{d.image.format, d.image.width, d.image.height, d.image.mip_levels, usage};
                auto img = vk::Image::create(*device_, desc, d.name);
                if (!img) return img.error();
                c.image = std::move(*img);
                c.info = d.image;
                c.usage = usage;
            }
            ctx.images_[r] = &c.image;
        } else {
            CachedBuffer& c = buffers_[d.name];
            const VkBufferUsageFlags usage = plan.buffer_usage[r];
            if (!c.buffer.valid() || c.size < d.size || (c.usage & usage) != usage) {
                auto buf = vk::Buffer::create(*device_, d.size, usage, vk::MemoryKind::DeviceLocal, d.name);
                if (!buf) return buf.error();
                c.buffer = std::move(*buf);
                c.size = d.size;
                c.usage = usage;
            }
            ctx.buffers_[r] = &c.buffer;
        }
    }
    return {};
}

Result<void> Executor::planFor(const Graph& graph) {
    graph.planKey(scratch_key_);
    if (plan_valid_ && scratch_key_ == plan_key_) return {};
    plan_valid_ = false;
    ++compilations_;
    auto compiled = graph.compile();
    if (!compiled) return compiled.error();
    plan_ = std::move(*compiled);
    std::swap(plan_key_, scratch_key_);
    plan_valid_ = true;
    return {};
}

void Executor::tapeBarriers(const std::vector<Barrier>& barriers, const PassContext& ctx) {
    if (barriers.empty()) return;
    std::vector<VkImageMemoryBarrier2>& images = image_barriers_;
    std::vector<VkBufferMemoryBarrier2>& buffers = buffer_barriers_;
    images.clear();
    buffers.clear();
    for (const Barrier& b : barriers) {
        if (b.is_image) {
            const vk::Image& img = ctx.image(b.resource);
            VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
            ib.srcStageMask = b.src_stage ? b.src_stage : VK_PIPELINE_STAGE_2_NONE;
            ib.srcAccessMask = b.src_access;
            ib.dstStageMask = b.dst_stage;
            ib.dstAccessMask = b.dst_access;
            ib.oldLayout = b.old_layout;
            ib.newLayout = b.new_layout;
            ib.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            ib.image = img.handle();
            ib.subresourceRange = {vk::aspectOf(img.desc().format), b.base_mip, b.mip_count, 0, 1};
            images.push_back(ib);
        } else {
            const vk::Buffer& buf = ctx.buffer(b.resource);
            VkBufferMemoryBarrier2 bb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
            bb.srcStageMask = b.src_stage;
            bb.srcAccessMask = b.src_access;
            bb.dstStageMask = b.dst_stage;
            bb.dstAccessMask = b.dst_access;
            bb.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            bb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
            bb.buffer = buf.handle();
            bb.offset = 0;
            bb.size = VK_WHOLE_SIZE;
            buffers.push_back(bb);
        }
    }
    VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    di.imageMemoryBarrierCount = static_cast<std::uint32_t>(images.size());
    di.pImageMemoryBarriers = images.data();
    di.bufferMemoryBarrierCount = static_cast<std::uint32_t>(buffers.size());
    di.pBufferMemoryBarriers = buffers.data();
    tape_.pipelineBarrier(di);
}

void Executor::tapePlan(const Graph& graph, const GraphPlan& plan, PassContext& ctx, bool outer_label) {
    // Labels only where the device has them: without, the tape (and what it costs) is as before.
    const bool labels = device_->debug_utils;
    if (labels && outer_label) tape_.beginLabel(vk::kDebugPrefix, "detect");
    std::uint32_t q = 0;
    for (const PlannedPass& planned : plan.order) {
        const PassDecl& p = graph.passes()[planned.pass];
        pending_names_.push_back(p.name);
        pending_stages_.push_back(p.stage);
        tapeBarriers(planned.barriers, ctx);
        if (labels) tape_.beginLabel(vk::kDebugPrefix, p.name);
        tape_.writeTimestamp(VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, queries_, q++);
        const std::size_t signals = tape_.signals();
        if (p.kind == PassKind::Raster) {
            std::vector<VkRenderingAttachmentInfo>& colors = colors_;
            colors.clear();
            VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            bool has_depth = false;
            std::uint32_t width = p.render_width, height = p.render_height;
            for (const Access& a : p.accesses) {
                if (a.use != Use::ColorAttachment && a.use != Use::DepthAttachment) continue;
                const vk::Image& img = ctx.image(a.resource);
                VkRenderingAttachmentInfo att{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
                att.imageView = img.levelView(0);
                att.loadOp = a.load_op;
                att.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
                att.clearValue = a.clear;
                if (width == 0) {
                    width = img.desc().width;
                    height = img.desc().height;
                }
                if (a.use == Use::ColorAttachment) {
                    att.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
                    colors.push_back(att);
                } else {
                    att.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
                    depth = att;
                    has_depth = true;
                }
            }
            ctx.render_width = width;
            ctx.render_height = height;
            VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
            ri.renderArea = {{0, 0}, {width, height}};
            ri.layerCount = 1;
            ri.colorAttachmentCount = static_cast<std::uint32_t>(colors.size());
            ri.pColorAttachments = colors.data();
            ri.pDepthAttachment = has_depth ? &depth : nullptr;
            tape_.beginRendering(ri);
            tape_.setViewport({0, 0, float(width), float(height), 0, 1});
            tape_.setScissor({{0, 0}, {width, height}});
            p.record(ctx);
            tape_.endRendering();
        } else {
            p.record(ctx);
        }
        // The first pass that sets a milestone's event: its start tells collect() when to look.
        if (tape_.signals() != signals && pending_signal_pass_ == kNoPass)
            pending_signal_pass_ = static_cast<std::uint32_t>(pending_names_.size() - 1);
        tape_.writeTimestamp(VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, queries_, q++);
        if (labels) tape_.endLabel();
    }
    tapeBarriers(plan.final_barriers, ctx);
    if (labels && outer_label) tape_.endLabel();
}

VkCommandBuffer Executor::directCommands() {
    went_direct_ = true;
    if (direct_error_) return recording_;
    if (!recording_) {
        held_valid_ = false;  // begin() resets the pool
        auto cmd = submission_.begin(vk::Submission::Reuse::Once);
        if (!cmd) {
            // Only out-of-memory gets here (the previous work was waited for). The callback
            // records into a command buffer that is not recording, which submit() never
            // submits: it returns this error instead.
            direct_error_ = cmd.error();
            recording_ = submission_.commandBuffer();
            return recording_;
        }
        recording_ = *cmd;
    }
    tape_.replay(device_->fns, recording_, replayed_);
    replayed_ = tape_.size();
    return recording_;
}

Result<void> Executor::settle(std::uint64_t timeout_ns) {
    if (!submission_.valid()) return {};
    return waitFor(submission_, timeout_ns);
}

bool Executor::busy() const {
    if (!submission_.valid() || !submission_.pending()) return false;
    auto ok = submission_.wait(0);
    return !ok && ok.error().vkResult() == VK_TIMEOUT;
}

std::uint64_t Executor::memoryBytes() const noexcept {
    std::uint64_t n = 0;
    for (const auto& [name, b] : buffers_) n += b.buffer.memoryBytes();
    for (const auto& [name, i] : images_) n += i.image.memoryBytes();
    return n;
}

Result<void> Executor::submit(const Graph& graph, std::uint64_t timeout_ns, SubmitTarget* target, bool signal) {
    const Clock::time_point t_start = Clock::now();
    pending_host_ = HostTimes{};
    if (auto ok = planFor(graph); !ok) return ok.error();
    const GraphPlan* plan = &plan_;
    const Clock::time_point t_compiled = Clock::now();
    pending_host_.compile_ms = msBetween(t_start, t_compiled);
    const auto& f = device_->fns;
    if (!submission_.valid()) {
        auto s = vk::Submission::create(*device_, "graph");
        if (!s) return s.error();
        submission_ = std::move(*s);
    }
    // Wait for the previous use before touching its resources or queries.
    if (auto ok = waitFor(submission_, timeout_ns); !ok) return ok.error();
    pending_milestone_ = std::exchange(next_milestone_, Milestone{});
    for (const vk::Event& e : pending_milestone_.events)
        if (auto ok = e.unset(); !ok) return ok.error();

    const auto pass_count = static_cast<std::uint32_t>(plan->order.size());
    const std::uint32_t needed = 2 * pass_count + 2;
    if (needed > query_capacity_) {
        held_valid_ = false;  // it writes timestamps into the pool destroyed here
        if (queries_) f.vkDestroyQueryPool(device_->device, queries_, device_->allocator());
        queries_ = VK_NULL_HANDLE;
        VkQueryPoolCreateInfo qi{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
        qi.queryType = VK_QUERY_TYPE_TIMESTAMP;
        qi.queryCount = needed;
        VkResult r = f.vkCreateQueryPool(device_->device, &qi, device_->allocator(), &queries_);
        if (r != VK_SUCCESS) return vk::vulkanError(r, "vkCreateQueryPool");
        vk::nameObject(*device_, queries_, "graph timestamps");
        query_capacity_ = needed;
    }
    f.vkResetQueryPool(device_->device, queries_, 0, query_capacity_);

    PassContext ctx;
    ctx.device = device_;
    ctx.tape_ = &tape_;
    ctx.executor_ = this;
    if (auto ok = prepareResources(graph, *plan, ctx); !ok) return ok.error();
    const bool into_engine = target && target->engine;
    recording_ = VK_NULL_HANDLE;
    replayed_ = 0;
    went_direct_ = false;
    direct_error_.reset();
    if (into_engine) {
        auto cmd = submission_.beginIn(*target->engine);
        if (!cmd) return cmd.error();
        recording_ = *cmd;
    }

    pending_names_.clear();
    pending_stages_.clear();
    pending_signal_pass_ = kNoPass;
    pending_culled_.clear();
    for (std::uint32_t c : plan->culled) pending_culled_.push_back(graph.passes()[c].name);
    tape_.clear();
    // The engine's command buffer gets its outer label from CollisionWorld::record, around
    // every executor that records into it.
    tapePlan(graph, *plan, ctx, !into_engine);
    if (direct_error_) return *direct_error_;
    // Nothing the held command buffer names was destroyed since it was recorded (a count
    // read after the tape was built: nothing the tape names is destroyed while it is).
    const std::uint64_t generation = device_->resource_generation.load(std::memory_order_relaxed);
    const bool reuse = !into_engine && !went_direct_ && held_valid_ && submission_.canResubmit() &&
                       held_generation_ == generation && tape_ == held_;
    if (!reuse) {
        if (!recording_) {
            held_valid_ = false;  // begin() resets the pool
            auto cmd = submission_.begin(into_engine || went_direct_ ? vk::Submission::Reuse::Once : vk::Submission::Reuse::Again);
            if (!cmd) return cmd.error();
            recording_ = *cmd;
        }
        tape_.replay(f, recording_, replayed_);
        replayed_ = tape_.size();
    }
    const Clock::time_point t_recorded = Clock::now();
    pending_host_.record_ms = msBetween(t_compiled, t_recorded);
    pending_host_.submissions = 1;
    if (into_engine) {
        // The engine submits the command buffer and orders it with its own semaphores.
        if (auto ok = submission_.submit(); !ok) return ok.error();
        pending_submitted_at_ = Clock::now();
        target->waits_submitted = target->signals_submitted = true;
        return {};
    }
    SubmitSync sync;
    if (target) {
        if (!target->waits_submitted) sync.wait = target->sync.wait;
        if (signal) sync.signal = target->sync.signal;
    }
    if (reuse) {
        if (auto ok = submission_.resubmit(sync); !ok) return ok.error();
        ++reuses_;
        pending_host_.reused = 1;
    } else {
        if (auto ok = submission_.submit(sync); !ok) return ok.error();
        if (!went_direct_) {
            std::swap(held_, tape_);
            held_generation_ = generation;
            held_valid_ = true;
        }
    }
    pending_submitted_at_ = Clock::now();
    pending_host_.submit_ms = msBetween(t_recorded, pending_submitted_at_);
    if (target) {
        target->waits_submitted = true;
        target->signals_submitted = target->signals_submitted || signal;
    }
    return {};
}

Result<void> Executor::waitForCollect(std::uint64_t timeout_ns) {
    if (poll_ns_ == 0 || !submission_.valid() || !submission_.pending()) return waitFor(submission_, timeout_ns);
    const Clock::time_point start = Clock::now();
    auto spent = [&] { return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count()); };
    // Sleep until kPollLeadNs before the expected end, if that is still ahead.
    const Clock::time_point expected = pending_submitted_at_ + std::chrono::nanoseconds(last_gpu_span_ns_);
    const auto ahead = std::chrono::duration_cast<std::chrono::nanoseconds>(expected - start).count();
    if (ahead > std::int64_t{kPollLeadNs}) {
        const std::uint64_t sleep_ns = std::min<std::uint64_t>(static_cast<std::uint64_t>(ahead) - kPollLeadNs, timeout_ns);
        auto done = submission_.waitFor(sleep_ns);
        if (!done) return done.error();
        if (*done == vk::Completion::Done) return {};
    }
    const std::uint64_t poll_from = spent();
    std::uint64_t next_hook = poll_from;
    while (spent() - poll_from < poll_ns_ && spent() < timeout_ns) {
        if (poll_hook_ && spent() >= next_hook) {
            poll_hook_();
            next_hook = spent() + kPollHookNs;
        }
        auto done = submission_.poll();
        if (!done) return done.error();
        if (*done == vk::Completion::Done) return {};
    }
    const std::uint64_t used = spent();
    auto done = submission_.waitFor(used < timeout_ns ? timeout_ns - used : 0);
    if (!done) return done.error();
    if (*done == vk::Completion::NotYet) return timeoutError(timeout_ns);
    return {};
}

Result<bool> Executor::waitForMilestone(const vk::Event& event, bool first, std::uint64_t timeout_ns) {
    const Clock::time_point start = Clock::now();
    auto spent = [&] { return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count()); };
    const auto ended = [&]() -> Result<bool> {  // the submission is done: set or never
        auto set = event.isSet();
        if (!set) return set.error();
        return *set;
    };
    if (!submission_.valid() || !submission_.pending()) return ended();
    // The first: asleep in the fence's wait until kPollLeadNs before where the last
    // submission's pass that sets it began (its timestamps: collect()). The later ones
    // follow it closely: polled at once.
    const Clock::time_point expected = pending_submitted_at_ + std::chrono::nanoseconds(last_milestone_ns_);
    const auto ahead = std::chrono::duration_cast<std::chrono::nanoseconds>(expected - start).count();
    if (first && ahead > std::int64_t{kPollLeadNs}) {
        auto done = submission_.waitFor(std::min<std::uint64_t>(static_cast<std::uint64_t>(ahead) - kPollLeadNs, timeout_ns));
        if (!done) return done.error();
        if (*done == vk::Completion::Done) return ended();
    }
    // Then polled (an event has no host wait): busy for at most the polling window, then
    // in short naps in the fence's wait, which also end when the submission does.
    const std::uint64_t poll_from = spent();
    const std::uint64_t window = std::max<std::uint64_t>(poll_ns_, 2 * kPollLeadNs);
    std::uint64_t next_hook = poll_from;
    while (spent() < timeout_ns) {
        auto set = event.isSet();
        if (!set) return set.error();
        if (*set) return true;
        if (poll_hook_ && spent() >= next_hook) {
            poll_hook_();
            next_hook = spent() + kPollHookNs;
        }
        auto done = spent() - poll_from < window ? submission_.poll() : submission_.waitFor(std::min<std::uint64_t>(kMilestoneNapNs, timeout_ns - std::min(timeout_ns, spent())));
        if (!done) return done.error();
        if (*done == vk::Completion::Done) return ended();
    }
    return false;
}

Result<ExecutionReport> Executor::collect(std::uint64_t timeout_ns) {
    const Clock::time_point t_wait = Clock::now();
    double milestone_ms = 0;
    if (!pending_milestone_.events.empty()) {
        const Milestone m = std::exchange(pending_milestone_, Milestone{});
        for (std::size_t k = 0; k < m.events.size(); ++k) {
            const auto used = static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t_wait).count());
            auto seen = waitForMilestone(m.events[k], k == 0, used < timeout_ns ? timeout_ns - used : 0);
            if (!seen) return seen.error();
            if (!*seen) break;
            const Clock::time_point t_seen = Clock::now();
            if (m.reached) m.reached(k);
            milestone_ms += msBetween(t_seen, Clock::now());
        }
        const auto used = static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - t_wait).count());
        timeout_ns = used < timeout_ns ? timeout_ns - used : 0;
    }
    if (auto ok = waitForCollect(timeout_ns); !ok) return ok.error();
    const Clock::time_point t_woken = Clock::now();
    ExecutionReport report;
    report.culled = pending_culled_;
    report.host = pending_host_;
    report.host.wait_ms = msBetween(t_wait, t_woken) - milestone_ms;
    report.host.milestone_ms = milestone_ms;
    const auto count = static_cast<std::uint32_t>(2 * pending_names_.size());
    if (count == 0) return report;
    std::vector<std::uint64_t> stamps(count);
    VkResult r = device_->fns.vkGetQueryPoolResults(device_->device, queries_, 0, count, stamps.size() * sizeof(std::uint64_t),
                                                    stamps.data(), sizeof(std::uint64_t),
                                                    VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT);
    if (r != VK_SUCCESS) return vk::vulkanError(r, "vkGetQueryPoolResults");
    // Mask to the valid bits so a wrapped counter does not give a huge time.
    const std::uint64_t mask = device_->timestamp_valid_bits >= 64 ? ~0ull : ((1ull << device_->timestamp_valid_bits) - 1);
    const double period_ms = device_->properties.limits.timestampPeriod * 1e-6;
    for (std::size_t i = 0; i < pending_names_.size(); ++i) {
        const std::uint64_t t0 = stamps[2 * i] & mask, t1 = stamps[2 * i + 1] & mask;
        report.passes.push_back({pending_names_[i], double((t1 - t0) & mask) * period_ms, pending_stages_[i]});
    }
    report.total_gpu_ms = double(((stamps[count - 1] & mask) - (stamps[0] & mask)) & mask) * period_ms;
    // Where the next milestone is looked for: the GPU time to the start of the first pass
    // that sets an event (the launch latency is within collect()'s kPollLeadNs of polling
    // ahead of it).
    if (pending_signal_pass_ != kNoPass)
        last_milestone_ns_ = static_cast<std::uint64_t>(
            double(((stamps[2 * pending_signal_pass_] & mask) - (stamps[0] & mask)) & mask) * period_ms * 1e6);
    report.host.gpu_span_ms = report.total_gpu_ms;
    last_gpu_span_ns_ = static_cast<std::uint64_t>(report.total_gpu_ms * 1e6);
    report.host.launch_wake_ms = std::max(0.0, msBetween(pending_submitted_at_, t_woken) - report.total_gpu_ms);
    return report;
}

Result<ExecutionReport> Executor::run(const Graph& graph, std::uint64_t timeout_ns) {
    if (auto ok = submit(graph, timeout_ns); !ok) return ok.error();
    return collect(timeout_ns);
}

}  // namespace vkcollide::graph
