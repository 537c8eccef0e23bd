// Scopes, the GPU timestamp ring and per-frame budget checks.
#include "engine/profiler/FrameProfiler.h"

#include "platforms/Clock.h"

#include <algorithm>
#include <functional>
#include <stdexcept>

namespace lpv::engine {
namespace {
double ms(uint64_t begin, uint64_t end) {
    return end > begin ? double(end - begin) / 1e6 : 0.0;
}
bool isGi(std::string_view path) {
    return path.starts_with("gi");
}
} // namespace

FrameProfiler::FrameProfiler(rhi::Device& device, platforms::PlatformProfile profile, ProfilerOptions options)
    : device_(device), profile_(std::move(profile)), x360_(platforms::loadPlatformProfile("x360")),
      ps3_(platforms::loadPlatformProfile("ps3")), options_(options),
      timingSource_(device.caps().timestampSource), frameCpu_(options.statsWindow),
      frameGpu_(options.statsWindow) {
    if (timingSource_ != rhi::TimestampSource::None && options_.gpuTiming)
        gpuSlots_ =
            std::min<uint32_t>(device.caps().maxTimestampsPerFrame, 2 + 2 * options_.maxScopesPerFrame);
    if (gpuSlots_ < 2) {
        gpuSlots_ = 0;
        timingSource_ = rhi::TimestampSource::None;
    }
    records_.resize(std::max<uint32_t>(options_.traceFrames, 8));
    for (FrameRecord& r : records_)
        r.samples.resize(options_.maxScopesPerFrame);
    notes_.resize(std::max<uint32_t>(options_.maxNotes, 2));
    stack_.reserve(64);
    scopes_.reserve(256);
    timestampScratch_.resize(gpuSlots_);
    resources_ = resourceSignature();
}

std::pair<uint64_t, uint64_t> FrameProfiler::resourceSignature() const {
    uint64_t count = 0;
    for (const auto& category : device_.allocations().categories())
        count += category.second.count;
    return {count, device_.allocations().totalBytes()};
}

FrameProfiler::~FrameProfiler() = default;

uint16_t FrameProfiler::internScope(std::string_view name, int32_t parent) {
    for (size_t i = 0; i < scopes_.size(); ++i)
        if (scopes_[i].parent == parent && scopes_[i].name == name) return uint16_t(i);
    if (scopes_.size() >= 0xffff) throw std::logic_error("profiler: too many distinct scopes");
    if (current_) current_->warmUp |= kWarmUpFirstRunOfPass;
    ScopeInfo info{std::string(name),
                   std::string(name),
                   parent,
                   0,
                   SampleWindow(options_.statsWindow),
                   SampleWindow(options_.statsWindow),
                   {},
                   0};
    if (parent >= 0) {
        info.path = scopes_[size_t(parent)].path + "/" + info.name;
        info.depth = scopes_[size_t(parent)].depth + 1;
    }
    scopes_.push_back(std::move(info));
    return uint16_t(scopes_.size() - 1);
}

void FrameProfiler::beginFrame(rhi::CommandList& cmd) {
    if (current_) throw std::logic_error("profiler: beginFrame() twice without endFrame()");
    resolveGpu();
    FrameRecord& r = records_[recorded_ % records_.size()];
    ++recorded_;
    r.frame = device_.frameIndex();
    r.cpuBegin = platforms::nowNanoseconds();
    r.cpuEnd = r.gpuBegin = r.gpuEnd = 0;
    r.gpuResolved = false;
    r.checked = false;
    r.sampleCount = 0;
    // What the frame starts with, until endFrame() takes what it ended with (a trace written
    // mid-frame shows this frame's, not an older frame's of the same slot).
    r.memoryTotal = device_.allocations().totalBytes();
    r.memoryGi = device_.allocations().bytesIn("gi");
    r.check = {};
    // Resources made since the last frame ended (a GI rebuild, the renderer's targets) belong to
    // this frame's warm-up.
    r.warmUp = 0;
    if (const auto resources = resourceSignature(); resources != resources_) {
        r.warmUp |= kWarmUpMadeResources;
        resources_ = resources;
    }
    r.commands = {};
    current_ = &r;
    frameCmd_ = &cmd;
    // Notes made since the last frame ended belong to this one.
    for (uint32_t i = 0; i < pendingNotes_; ++i) {
        Note& n = notes_[(noted_ - 1 - i) % notes_.size()];
        n.frame = r.frame;
        n.cpuTime = r.cpuBegin;
    }
    pendingNotes_ = 0;
    if (gpuSlots_) cmd.writeTimestamp(0);
}

FrameProfiler::Scope FrameProfiler::scope(std::string_view name, rhi::CommandList* gpu) {
    if (!current_)
        throw std::logic_error("profiler: scope '" + std::string(name) + "' opened outside a frame");
    const int32_t parent = stack_.empty() ? -1 : int32_t(stack_.back().scope);
    const uint16_t id = internScope(name, parent);
    uint32_t sampleIndex = UINT32_MAX;
    if (current_->sampleCount < current_->samples.size()) {
        sampleIndex = current_->sampleCount++;
        Sample& s = current_->samples[sampleIndex];
        s = Sample{};
        s.scope = id;
        const uint32_t slot = 2 + 2 * sampleIndex;
        s.gpuTimed = gpu && slot + 1 < gpuSlots_;
        if (s.gpuTimed) gpu->writeTimestamp(slot);
        s.cpuBegin = platforms::nowNanoseconds();
    }
    stack_.push_back({id, sampleIndex, gpu, frameCmd_->counts()});
    scopes_[id].lastFrame = current_->frame;
    return Scope(this);
}

void FrameProfiler::closeScope() {
    const Open open = stack_.back();
    stack_.pop_back();
    const rhi::CommandCounts commands = frameCmd_->counts() - open.commands;
    ScopeInfo& info = scopes_[open.scope];
    if (info.commandsFrame != current_->frame) {
        info.commands = {};
        info.commandsFrame = current_->frame;
    }
    info.commands += commands;
    if (open.sample == UINT32_MAX) return; // over maxScopesPerFrame: not recorded
    Sample& s = current_->samples[open.sample];
    s.commands = commands;
    s.cpuEnd = platforms::nowNanoseconds();
    if (s.gpuTimed) open.gpu->writeTimestamp(3 + 2 * open.sample);
}

std::vector<size_t> FrameProfiler::scopesInTreeOrder() const {
    std::vector<size_t> order;
    order.reserve(scopes_.size());
    std::function<void(int32_t)> visit = [&](int32_t parent) {
        for (size_t i = 0; i < scopes_.size(); ++i)
            if (scopes_[i].parent == parent) {
                order.push_back(i);
                visit(int32_t(i));
            }
    };
    visit(-1);
    return order;
}

WorkCounts FrameProfiler::inclusiveWork(size_t scope) const {
    WorkCounts w = scopes_[scope].work;
    for (size_t i = scope + 1; i < scopes_.size(); ++i)
        for (int32_t p = scopes_[i].parent; p >= 0; p = scopes_[size_t(p)].parent)
            if (size_t(p) == scope) {
                w += scopes_[i].work;
                break;
            }
    return w;
}

FrameProfiler::ScopePrediction FrameProfiler::predicted(size_t scope) const {
    const FrameRecord* last = nullptr;
    forEachFrame([&](const FrameRecord& r) {
        if (r.frame == scopes_[scope].lastFrame) last = &r;
    });
    // A frame past its sample slots (ProfilerOptions::maxScopesPerFrame) recorded no sample of
    // the scope: its own last work, as for a frame no longer recorded.
    bool sampled = false;
    if (last)
        for (uint32_t k = 0; k < last->sampleCount && !sampled; ++k)
            sampled = last->samples[k].scope == scope;
    if (!sampled) {
        const WorkCounts work = inclusiveWork(scope);
        return {predictCost(work, x360_.throughput), predictCost(work, ps3_.throughput),
                predictCost(work, profile_.throughput)};
    }
    ScopePrediction out;
    double largest = -1.0;
    for (uint32_t k = 0; k < last->sampleCount; ++k) {
        const Sample& sample = last->samples[k];
        bool under = false;
        for (int32_t s = int32_t(sample.scope); s >= 0 && !under; s = scopes_[size_t(s)].parent)
            under = size_t(s) == scope;
        if (!under) continue;
        const CostPrediction x360 = predictCost(sample.work, x360_.throughput);
        const CostPrediction ps3 = predictCost(sample.work, ps3_.throughput);
        const CostPrediction active = predictCost(sample.work, profile_.throughput);
        out.x360.ms += x360.ms;
        out.ps3.ms += ps3.ms;
        out.active.ms += active.ms;
        if (x360.ms > largest) {
            largest = x360.ms;
            out.x360.bottleneck = x360.bottleneck;
            out.ps3.bottleneck = ps3.bottleneck;
            out.active.bottleneck = active.bottleneck;
        }
    }
    return out;
}

void FrameProfiler::setWork(const WorkCounts& work) {
    if (stack_.empty()) throw std::logic_error("profiler: setWork() with no open scope");
    const Open& open = stack_.back();
    scopes_[open.scope].work = work;
    if (open.sample != UINT32_MAX) current_->samples[open.sample].work = work;
}

void FrameProfiler::setTimedIn(std::string_view path) {
    if (stack_.empty()) throw std::logic_error("profiler: setTimedIn() with no open scope");
    std::string& timedIn = scopes_[stack_.back().scope].timedIn;
    if (timedIn != path) timedIn = path; // allocates the first frame only
}

static void writeNote(FrameProfiler::Note& n, std::string_view topic, std::string_view text) {
    const auto copy = [](std::string_view from, auto& to) {
        const size_t length = std::min(from.size(), to.size() - 1);
        std::copy_n(from.data(), length, to.data());
        to[length] = '\0';
    };
    copy(topic, n.topicBuffer);
    copy(text, n.textBuffer);
}

void FrameProfiler::note(std::string_view topic, std::string_view text, uint64_t frame) {
    if (pendingNotes_ + 1 >= notes_.size()) {
        ++pendingLost_;
        return;
    }
    Note& n = notes_[noted_ % notes_.size()];
    ++noted_;
    writeNote(n, topic, text);
    n.frame = frame;
    n.cpuTime = 0; // a frame no longer recorded: the trace puts the note at its start (before_trace)
    forEachFrame([&](const FrameRecord& r) {
        if (r.frame == frame) n.cpuTime = r.cpuEnd;
    });
    // Notes waiting for the next frame stay the newest in the ring (forEachNote leaves them out).
    for (uint64_t i = 0; i < pendingNotes_; ++i)
        std::swap(notes_[(noted_ - 1 - i) % notes_.size()], notes_[(noted_ - 2 - i) % notes_.size()]);
}

void FrameProfiler::note(std::string_view topic, std::string_view text) {
    if (!current_ && pendingNotes_ + 1 >= notes_.size()) {
        ++pendingLost_; // a flood between two frames: keep the first ones and a slot for the last frame's
        return;
    }
    Note& n = notes_[noted_ % notes_.size()];
    ++noted_;
    writeNote(n, topic, text);
    if (current_) {
        n.frame = current_->frame;
        n.cpuTime = platforms::nowNanoseconds();
    } else {
        n.frame = 0;
        n.cpuTime = 0;
        ++pendingNotes_;
    }
}

void FrameProfiler::endFrame(rhi::CommandList& cmd) {
    if (!current_) throw std::logic_error("profiler: endFrame() without beginFrame()");
    if (!stack_.empty())
        throw std::logic_error("profiler: scope '" + scopes_[stack_.back().scope].path +
                               "' still open at endFrame()");
    if (gpuSlots_) cmd.writeTimestamp(1);
    current_->cpuEnd = platforms::nowNanoseconds();
    current_->commands = cmd.counts();
    // Sampled at the end: what the frame made lazily (the renderer's targets on its first
    // render(), the volumes of a rebuild) is memory it ran with.
    current_->memoryTotal = device_.allocations().totalBytes();
    current_->memoryGi = device_.allocations().bytesIn("gi");
    frameCpu_.add(ms(current_->cpuBegin, current_->cpuEnd));
    forEachScopeIn(*current_, [&](uint16_t scope, double cpuMs, double) { scopes_[scope].cpuMs.add(cpuMs); });
    if (const auto resources = resourceSignature(); resources != resources_) {
        current_->warmUp |= kWarmUpMadeResources;
        resources_ = resources;
    }
    if (current_->warmUp) {
        ++warmUp_.frames;
        warmUp_.madeResources += current_->warmUp & kWarmUpMadeResources ? 1 : 0;
        warmUp_.firstRunOfPass += current_->warmUp & kWarmUpFirstRunOfPass ? 1 : 0;
    }
    if (!gpuSlots_) finishCheck(*current_);
    current_ = nullptr;
    frameCmd_ = nullptr;
}

void FrameProfiler::collectPending() {
    if (current_) throw std::logic_error("profiler: collectPending() inside a frame");
    for (uint32_t i = 0; i <= device_.caps().framesInFlight; ++i) {
        device_.beginFrame();
        resolveGpu();
        device_.endFrame();
    }
}

void FrameProfiler::resolveGpu() {
    if (!gpuSlots_) return;
    const uint64_t now = device_.frameIndex();
    const uint64_t keep = device_.caps().framesInFlight + 1;
    const uint64_t n = std::min<uint64_t>(recorded_, std::min<uint64_t>(records_.size(), keep + 2));
    // Oldest first, so budget checks arrive in frame order.
    for (uint64_t i = recorded_ - n; i < recorded_; ++i) {
        FrameRecord& r = records_[i % records_.size()];
        if (r.checked || r.cpuEnd == 0) continue;
        const size_t slots = std::min<size_t>(gpuSlots_, 2 + 2 * size_t(r.sampleCount));
        if (device_.readTimestamps(r.frame, std::span(timestampScratch_.data(), slots))) {
            r.gpuResolved = true;
            r.gpuBegin = timestampScratch_[0];
            r.gpuEnd = timestampScratch_[1];
            frameGpu_.add(ms(r.gpuBegin, r.gpuEnd));
            for (uint32_t k = 0; k < r.sampleCount; ++k) {
                Sample& s = r.samples[k];
                if (!s.gpuTimed || 3 + 2 * k >= slots) {
                    s.gpuTimed = false;
                    continue;
                }
                s.gpuBegin = timestampScratch_[2 + 2 * k];
                s.gpuEnd = timestampScratch_[3 + 2 * k];
            }
            forEachScopeIn(r, [&](uint16_t scope, double, double gpuMs) {
                if (gpuMs >= 0.0) scopes_[scope].gpuMs.add(gpuMs);
            });
            finishCheck(r);
        } else if (r.frame + keep <= now) {
            // The device reused this frame's timestamp storage before we saw it: judge it on CPU time.
            ++gpuLost_;
            finishCheck(r);
        }
    }
}

void FrameProfiler::finishCheck(FrameRecord& r) {
    r.checked = true;
    FrameBudgetCheck& c = r.check;
    c.frame = r.frame;
    c.frameMs = r.gpuResolved ? ms(r.gpuBegin, r.gpuEnd) : ms(r.cpuBegin, r.cpuEnd);
    for (uint32_t k = 0; k < r.sampleCount; ++k) {
        const Sample& s = r.samples[k];
        const ScopeInfo& info = scopes_[s.scope];
        if (!isGi(info.path)) continue;
        if (info.depth == 0)
            c.giMs += r.gpuResolved && s.gpuTimed ? ms(s.gpuBegin, s.gpuEnd) : ms(s.cpuBegin, s.cpuEnd);
        // Passes run one after another, each as long as its own busiest unit: predict each, then
        // add (as the cost model's calibration does), rather than predicting the frame's summed work.
        if (s.work.empty()) continue;
        c.giPredictedX360Ms += predictCost(s.work, x360_.throughput).ms;
        c.giPredictedPs3Ms += predictCost(s.work, ps3_.throughput).ms;
        c.giPredictedMs += predictCost(s.work, profile_.throughput).ms;
    }
    c.frameOverBudget = c.frameMs > profile_.frameBudgetMs;
    c.giOverBudget = c.giMs > profile_.giBudgetMs;
    c.giPredictedOverBudget = profile_.giTimePredicted && c.giPredictedMs > profile_.giBudgetMs;
    c.giBudgetedMs = profile_.giTimePredicted ? c.giPredictedMs : c.giMs;
    lastCheck_ = c;
    ++framesChecked_;
    if (c.frameOverBudget || c.giOverBudget || c.giPredictedOverBudget) ++framesOverBudget_;
    if (c.giOverBudget || c.giPredictedOverBudget) ++framesOverGiBudget_;
    if (r.warmUp) {
        ++warmUp_.checked;
        warmUp_.overBudget += c.frameOverBudget || c.giOverBudget || c.giPredictedOverBudget ? 1 : 0;
        warmUp_.overGiBudget += c.giOverBudget || c.giPredictedOverBudget ? 1 : 0;
    }
}

} // namespace lpv::engine
