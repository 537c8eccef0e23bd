// Command recording for the Vulkan backend.
#include "VkCommandList.h"
#include "../src/DescValidation.h"

#include "VkBarriers.h"
#include "VkFormats.h"
#include "VulkanDevice.h"

#include "rhi/Error.h"

#include <algorithm>
#include <string>

namespace lpv::rhi::vk {
namespace {

const char* kindName(int kind) {
    static const char* const names[] = {"nothing", "a uniform buffer", "a storage buffer",
                                        "a sampled texture", "a storage image"};
    return names[kind];
}

} // namespace

void VulkanCommandList::begin(VkCommandBuffer cmd) {
    cmd_ = cmd;
    clearBindings();
    graphics_ = {};
    compute_ = {};
    inPass_ = false;
    passTargetCount_ = 0;
    markerDepth_ = 0;
    owed_ = false;
    passOwed_ = false;
    rendering_ = false;
    writtenCount_ = readCount_ = 0;
    writtenOverflow_ = readOverflow_ = false;
    vertexBuffers_ = {};
    indexBuffer_ = 0;
    indexOffset_ = 0;
}

void VulkanCommandList::resetCounts() {
    CommandList::resetCounts();
    barrierBase_ = pipelineBarrierCalls();
}

CommandCounts VulkanCommandList::counts() const {
    CommandCounts c = counts_;
    c.barriers = uint32_t(pipelineBarrierCalls() - barrierBase_);
    return c;
}

void VulkanCommandList::finish() {
    if (inPass_) throw Error("endFrame() inside a render pass: call endRenderPass() first");
    // Every write visible to whatever is submitted next (the next frame begins with no barrier of
    // its own) and available to the host (MemoryAccess::HostRead buffers, read after the frame's
    // fence), in one call.
    BarrierBatch batch(cmd_);
    payPass(batch);
    payOwed(&batch);
    batch.memory();
    batch.hostRead();
    batch.flush();
    while (markerDepth_ > 0) {
        endLabel();
        --markerDepth_;
    }
}

void VulkanCommandList::requireFrame(const char* what) const {
    if (!device_.inFrame()) throw Error(std::string(what) + " outside beginFrame()/endFrame()");
}

void VulkanCommandList::requirePass(bool inside, const char* what) const {
    requireFrame(what);
    if (inPass_ != inside)
        throw Error(std::string(what) + (inside ? " outside a render pass" : " inside a render pass"));
}

VulkanCommandList::Bound& VulkanCommandList::slot(uint32_t binding, const char* what) {
    requireFrame(what);
    if (binding >= kMaxBindings)
        throw Error(std::string(what) + ": binding " + std::to_string(binding) +
                    " >= " + std::to_string(kMaxBindings));
    return bound_[binding];
}

void VulkanCommandList::clearBindings() {
    for (Bound& b : bound_)
        b.kind = BoundKind::None;
}

void VulkanCommandList::beginLabel(const char* name) {
    const VulkanContext& ctx = device_.context();
    if (!ctx.cmdBeginDebugUtilsLabel) return;
    VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
    label.pLabelName = name ? name : "";
    ctx.cmdBeginDebugUtilsLabel(cmd_, &label);
}

void VulkanCommandList::endLabel() {
    const VulkanContext& ctx = device_.context();
    if (ctx.cmdEndDebugUtilsLabel) ctx.cmdEndDebugUtilsLabel(cmd_);
}

void VulkanCommandList::beginRenderPass(const RenderPassDesc& desc) {
    requirePass(false, "beginRenderPass");
    if (desc.colorCount > RenderPassDesc::kMaxColorTargets)
        throw Error("beginRenderPass: more than 8 color targets");
    if (desc.colorCount == 0 && !desc.depth.texture) throw Error("beginRenderPass: no color or depth target");
    device_.flushNewTextures(cmd_);

    // The attachments, and the layout each is drawn in: in GENERAL where that is its home (a
    // storage image, such as the LPV's injection volumes, or every texture with unified layouts),
    // so it needs no move there and back around each pass (30% of the injection's time on an
    // NVIDIA H100 when it moved).
    std::array<PassTarget, RenderPassDesc::kMaxColorTargets + 1> targets{};
    uint32_t targetCount = 0;
    passExtent_ = {0, 0};
    passColors_ = {};
    passDepth_ = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    const bool layered = isLayeredPass(desc, device_.caps());
    uint32_t layerCount = 1;
    auto checkExtent = [&](const VulkanTexture& t, uint32_t mip) {
        const VkExtent2D e{t.width(mip), t.height(mip)};
        if (targetCount == 0) {
            passExtent_ = e;
        } else if (e.width < passExtent_.width || e.height < passExtent_.height) {
            throw Error("beginRenderPass '" + std::string(desc.debugName) + "': target '" + t.desc.debugName +
                        "' is smaller than the first target");
        }
    };
    for (uint32_t i = 0; i < desc.colorCount; ++i) {
        const ColorAttachment& a = desc.colors[i];
        VulkanTexture& t = device_.textures.get(a.texture);
        if (!(t.desc.usage & kTextureColorTarget) || isDepthFormat(t.desc.format))
            throw Error("beginRenderPass: texture '" + t.desc.debugName + "' is not a color target");
        if (a.mipLevel >= t.desc.mipLevels || a.layer >= t.targetLayers(a.mipLevel))
            throw Error("beginRenderPass: texture '" + t.desc.debugName + "' has no mip " +
                        std::to_string(a.mipLevel) + " layer " + std::to_string(a.layer));
        checkExtent(t, a.mipLevel);
        if (layered)
            layerCount = layeredTargetLayers(desc, i, t.desc, t.targetLayers(a.mipLevel), layerCount);
        const VkImageLayout layout = t.home == VK_IMAGE_LAYOUT_GENERAL
                                         ? VK_IMAGE_LAYOUT_GENERAL
                                         : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
        VkRenderingAttachmentInfo& c = passColors_[i];
        c = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
        c.imageView =
            layered ? t.layeredViews[a.mipLevel] : t.targetViews[t.targetBase[a.mipLevel] + a.layer];
        c.imageLayout = layout;
        c.loadOp = toVkLoadOp(a.load);
        c.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        if (isIntegerFormat(t.desc.format)) {
            for (int k = 0; k < 4; ++k)
                c.clearValue.color.uint32[k] = uint32_t(std::max(0.0f, a.clearColor[k]));
        } else {
            for (int k = 0; k < 4; ++k)
                c.clearValue.color.float32[k] = a.clearColor[k];
        }
        targets[targetCount++] = {a.texture, a.mipLevel, layout};
    }
    if (desc.depth.texture) {
        const DepthAttachment& a = desc.depth;
        VulkanTexture& t = device_.textures.get(a.texture);
        if (!isDepthFormat(t.desc.format) || !(t.desc.usage & (kTextureDepthTarget | kTextureColorTarget)))
            throw Error("beginRenderPass: texture '" + t.desc.debugName + "' is not a depth target");
        if (a.layer >= t.targetLayers(0))
            throw Error("beginRenderPass: depth texture '" + t.desc.debugName + "' has no layer " +
                        std::to_string(a.layer));
        checkExtent(t, 0);
        const VkImageLayout layout = t.home == VK_IMAGE_LAYOUT_GENERAL
                                         ? VK_IMAGE_LAYOUT_GENERAL
                                         : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
        passDepth_.imageView = t.targetViews[t.targetBase[0] + a.layer];
        passDepth_.imageLayout = layout;
        passDepth_.loadOp = toVkLoadOp(a.load);
        passDepth_.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
        passDepth_.clearValue.depthStencil = {a.clearDepth, a.clearStencil};
        targets[targetCount++] = {a.texture, 0, layout};
    }

    passInfo_ = {VK_STRUCTURE_TYPE_RENDERING_INFO};
    passInfo_.renderArea = {{0, 0}, passExtent_};
    passInfo_.layerCount = layerCount;
    passInfo_.colorAttachmentCount = desc.colorCount;
    passInfo_.pColorAttachments = passColors_.data();
    passInfo_.pDepthAttachment = desc.depth.texture ? &passDepth_ : nullptr;
    // A depth format with a stencil: one attachment, both aspects.
    const bool stencil =
        desc.depth.texture && hasStencil(device_.textures.get(desc.depth.texture).desc.format);
    passInfo_.pStencilAttachment = stencil ? &passDepth_ : nullptr;

    inPass_ = true;
    rendering_ = false;
    // With unified layouts a pass has no moves of its own: it begins at its first draw, when what
    // the draws bind is known, behind a barrier only if they or its targets meet a hazard.
    if (!deferredBegin()) {
        // Every attachment moves to its attachment layout before rendering begins (no barriers
        // inside a dynamic rendering instance), in one call with what dispatches and the last pass
        // owe; the last pass's targets this one draws to stay where they are.
        BarrierBatch barriers(cmd_);
        payPass(barriers, std::span(targets.data(), targetCount));
        payOwed(&barriers);
        for (uint32_t i = 0; i < targetCount; ++i)
            barriers.transition(device_.textures.get(targets[i].texture), targets[i].mip, 1,
                                targets[i].layout);
    }
    passTargets_ = targets;
    passTargetCount_ = targetCount;
    beginLabel(desc.debugName);
    if (!deferredBegin()) startRendering(nullptr);

    // The RHI's rule: viewport and scissor start as the whole first target.
    setViewport({0.0f, 0.0f, float(passExtent_.width), float(passExtent_.height), 0.0f, 1.0f});
    setScissor(0, 0, passExtent_.width, passExtent_.height);
}

bool VulkanCommandList::deferredBegin() const {
    return device_.unifiedImageLayouts();
}

void VulkanCommandList::startRendering(const VulkanPipeline* firstDraw) {
    if (deferredBegin()) {
        // Its targets (moved only if something left them elsewhere) and the first draw's
        // bindings: a barrier only at a hazard.
        BarrierBatch barriers(cmd_);
        bool hazard = device_.conservativeBarriers();
        for (uint32_t i = 0; i < passTargetCount_; ++i) {
            VulkanTexture& t = device_.textures.get(passTargets_[i].texture);
            barriers.transition(t, passTargets_[i].mip, 1, passTargets_[i].layout);
            hazard = hazard || owedHazard(uint64_t(t.image), true);
        }
        if (firstDraw) hazard = hazard || drawHazard(*firstDraw);
        if (hazard || !barriers.empty()) payOwed(&barriers);
    }
    vkCmdBeginRendering(cmd_, &passInfo_);
    rendering_ = true;
}

void VulkanCommandList::beforeDraw(const VulkanPipeline& p) {
    if (!deferredBegin()) return;
    if (!rendering_) {
        startRendering(&p);
        return;
    }
    // A later draw binds what an earlier command left unordered (the first draw's bindings were
    // ordered at the begin): the pass stops for the barrier and goes on where it was.
    if (!drawHazard(p)) return;
    vkCmdEndRendering(cmd_);
    for (uint32_t i = 0; i < passTargetCount_; ++i)
        owe(uint64_t(device_.textures.get(passTargets_[i].texture).image), true);
    payOwed();
    for (VkRenderingAttachmentInfo& c : passColors_)
        c.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    passDepth_.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    vkCmdBeginRendering(cmd_, &passInfo_);
}

bool VulkanCommandList::drawHazard(const VulkanPipeline& p) const {
    if (dispatchHazard(p) || owedHazard(indexBuffer_, false)) return true;
    return std::any_of(vertexBuffers_.begin(), vertexBuffers_.end(),
                       [&](uint64_t b) { return owedHazard(b, false); });
}

void VulkanCommandList::noteDrawAccesses(const VulkanPipeline& p) {
    if (!deferredBegin()) return;
    noteDispatchAccesses(p);
    owe(indexBuffer_, false);
    for (uint64_t b : vertexBuffers_)
        owe(b, false);
}

void VulkanCommandList::endRenderPass() {
    requirePass(true, "endRenderPass");
    if (!rendering_) startRendering(nullptr); // no draws: the begin still clears
    vkCmdEndRendering(cmd_);
    endLabel();
    inPass_ = false;
    rendering_ = false;
    if (deferredBegin()) {
        // Its targets are written like a dispatch's storage images: owed to whatever touches them.
        for (uint32_t i = 0; i < passTargetCount_; ++i)
            owe(uint64_t(device_.textures.get(passTargets_[i].texture).image), true);
        passTargetCount_ = 0;
        if (device_.conservativeBarriers()) payOwed();
        return;
    }
    // Its barrier is owed to the next command (payPass); at once under the conservative rule.
    passOwed_ = true;
    if (device_.conservativeBarriers()) {
        BarrierBatch barriers(cmd_);
        payPass(barriers);
    }
}

bool VulkanCommandList::payPass(BarrierBatch& batch, std::span<const PassTarget> keep) {
    if (!passOwed_) return false;
    for (uint32_t i = 0; i < passTargetCount_; ++i) {
        const PassTarget& t = passTargets_[i];
        if (!device_.textures.contains(t.texture)) continue;
        const bool kept = std::any_of(keep.begin(), keep.end(), [&](const PassTarget& k) {
            return k.texture == t.texture && (k.mip == t.mip || k.mip == PassTarget::kAllMips);
        });
        if (!kept) batch.transitionHome(device_.textures.get(t.texture));
    }
    passTargetCount_ = 0;
    passOwed_ = false;
    // Writes of the pass (attachments and any storage writes of its shaders) become visible to
    // everything recorded later.
    batch.memory();
    return true;
}

void VulkanCommandList::payAll() {
    if (!passOwed_ && !owed_) return;
    BarrierBatch batch(cmd_);
    payPass(batch);
    payOwed(&batch);
}

void VulkanCommandList::setViewport(const Viewport& vp) {
    requireFrame("setViewport");
    // No y-flip: NDC y = -1 lands on framebuffer row 0, which is memory row 0 (the RHI convention).
    const VkViewport v{vp.x, vp.y, vp.width, vp.height, vp.minDepth, vp.maxDepth};
    vkCmdSetViewport(cmd_, 0, 1, &v);
}

void VulkanCommandList::setScissor(int32_t x, int32_t y, uint32_t width, uint32_t height) {
    requireFrame("setScissor");
    // Vulkan rejects negative offsets; clip the rectangle to the framebuffer's origin instead.
    clipScissorToOrigin(x, y, width, height);
    const VkRect2D r{{x, y}, {width, height}};
    vkCmdSetScissor(cmd_, 0, 1, &r);
}

void VulkanCommandList::bindPipeline(GraphicsPipelineHandle pipeline) {
    requireFrame("bindPipeline");
    const VulkanPipeline& p = device_.graphicsPipelines.get(pipeline);
    vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_GRAPHICS, p.pipeline);
    clearBindings();
    graphics_ = pipeline;
}

void VulkanCommandList::bindPipeline(ComputePipelineHandle pipeline) {
    requireFrame("bindPipeline");
    const VulkanPipeline& p = device_.computePipelines.get(pipeline);
    vkCmdBindPipeline(cmd_, VK_PIPELINE_BIND_POINT_COMPUTE, p.pipeline);
    clearBindings();
    compute_ = pipeline;
}

void VulkanCommandList::bindVertexBuffer(uint32_t slotIndex, BufferHandle buffer, uint64_t offset) {
    requireFrame("bindVertexBuffer");
    const VulkanBuffer& b = device_.buffers.get(buffer);
    if (!(b.desc.usage & kBufferVertex)) throw Error("buffer '" + b.desc.debugName + "' lacks kBufferVertex");
    if (slotIndex >= vertexBuffers_.size())
        throw Error("bindVertexBuffer: slot " + std::to_string(slotIndex) +
                    " >= " + std::to_string(vertexBuffers_.size()));
    vkCmdBindVertexBuffers(cmd_, slotIndex, 1, &b.buffer, &offset);
    vertexBuffers_[slotIndex] = uint64_t(b.buffer);
}

void VulkanCommandList::bindIndexBuffer(BufferHandle buffer, IndexType type, uint64_t offset) {
    requireFrame("bindIndexBuffer");
    const VulkanBuffer& b = device_.buffers.get(buffer);
    if (!(b.desc.usage & kBufferIndex)) throw Error("buffer '" + b.desc.debugName + "' lacks kBufferIndex");
    vkCmdBindIndexBuffer(cmd_, b.buffer, offset,
                         type == IndexType::Uint16 ? VK_INDEX_TYPE_UINT16 : VK_INDEX_TYPE_UINT32);
    indexBuffer_ = uint64_t(b.buffer);
    indexOffset_ = offset;
}

void VulkanCommandList::bindBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset, uint64_t size,
                                   bool storage) {
    Bound& s = slot(binding, storage ? "bindStorageBuffer" : "bindUniformBuffer");
    const VulkanBuffer& b = device_.buffers.get(buffer);
    const uint32_t need = storage ? kBufferStorage : kBufferUniform;
    if (!(b.desc.usage & need))
        throw Error("buffer '" + b.desc.debugName +
                    (storage ? "' lacks kBufferStorage" : "' lacks kBufferUniform"));
    if (offset >= b.desc.size) throw Error("buffer '" + b.desc.debugName + "': binding offset past its end");
    if (size == kWholeSize) size = b.desc.size - offset;
    if (offset + size > b.desc.size)
        throw Error("buffer '" + b.desc.debugName + "': bound range exceeds its size");
    s.kind = storage ? BoundKind::StorageBuffer : BoundKind::UniformBuffer;
    s.buffer = {b.buffer, offset, size};
    s.resource = uint64_t(b.buffer);
}

void VulkanCommandList::bindUniformBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset,
                                          uint64_t size) {
    bindBuffer(binding, buffer, offset, size, false);
}

void VulkanCommandList::bindStorageBuffer(uint32_t binding, BufferHandle buffer, uint64_t offset,
                                          uint64_t size) {
    bindBuffer(binding, buffer, offset, size, true);
}

void VulkanCommandList::bindTexture(uint32_t binding, TextureHandle texture, SamplerHandle sampler) {
    Bound& s = slot(binding, "bindTexture");
    const VulkanTexture& t = device_.textures.get(texture);
    const VulkanSampler& smp = device_.samplers.get(sampler);
    if (!(t.desc.usage & kTextureSampled))
        throw Error("texture '" + t.desc.debugName + "' lacks kTextureSampled");
    // Integer formats have no filtering in Vulkan (or GL); a linear sampler would read garbage.
    if (isIntegerFormat(t.desc.format) &&
        (smp.desc.minFilter == Filter::Linear || smp.desc.magFilter == Filter::Linear ||
         (smp.desc.mipFilter == Filter::Linear && t.desc.mipLevels > 1)))
        throw Error("texture '" + t.desc.debugName + "' (" + std::string(formatName(t.desc.format)) +
                    ") cannot be sampled with a linear filter");
    s.kind = BoundKind::Texture;
    s.image = {smp.sampler, t.sampledView, t.home};
    s.resource = uint64_t(t.image);
}

void VulkanCommandList::bindStorageImage(uint32_t binding, TextureHandle texture, uint32_t mipLevel) {
    Bound& s = slot(binding, "bindStorageImage");
    validateStorageImageBinding(binding, device_.caps(), "bindStorageImage");
    const VulkanTexture& t = device_.textures.get(texture);
    if (!(t.desc.usage & kTextureStorage))
        throw Error("texture '" + t.desc.debugName + "' lacks kTextureStorage");
    if (mipLevel >= t.desc.mipLevels)
        throw Error("texture '" + t.desc.debugName + "' has no mip " + std::to_string(mipLevel));
    s.kind = BoundKind::StorageImage;
    s.image = {VK_NULL_HANDLE, t.mipViews[mipLevel], VK_IMAGE_LAYOUT_GENERAL};
    s.resource = uint64_t(t.image);
}

void VulkanCommandList::pushUniforms(uint32_t binding, const void* data, uint32_t size) {
    Bound& s = slot(binding, "pushUniforms");
    if (!data || size == 0) throw Error("pushUniforms: no data");
    const uint64_t offset = device_.pushToRing(data, size);
    s.kind = BoundKind::UniformBuffer;
    s.buffer = {device_.ringBuffer(), offset, size};
    s.resource = 0; // written by the host before the frame is submitted: no hazard
}

void VulkanCommandList::pushBindings(const VulkanPipeline& p) {
    std::array<VkWriteDescriptorSet, kMaxBindings> writes;
    uint32_t count = 0;
    for (const PipelineBinding& pb : p.bindings) {
        BoundKind want = BoundKind::None;
        switch (pb.type) {
        case VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER:
            want = BoundKind::UniformBuffer;
            break;
        case VK_DESCRIPTOR_TYPE_STORAGE_BUFFER:
            want = BoundKind::StorageBuffer;
            break;
        case VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER:
            want = BoundKind::Texture;
            break;
        case VK_DESCRIPTOR_TYPE_STORAGE_IMAGE:
            want = BoundKind::StorageImage;
            break;
        default:
            break;
        }
        const BoundKind have = pb.binding < kMaxBindings ? bound_[pb.binding].kind : BoundKind::None;
        if (have != want)
            throw Error("pipeline '" + p.name + "': binding " + std::to_string(pb.binding) + " expects " +
                        kindName(int(want)) + " but " + kindName(int(have)) + " is bound");
        const Bound& b = bound_[pb.binding];
        VkWriteDescriptorSet& w = writes[count++];
        w = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        w.dstBinding = pb.binding;
        w.descriptorCount = 1;
        w.descriptorType = pb.type;
        if (want == BoundKind::UniformBuffer || want == BoundKind::StorageBuffer)
            w.pBufferInfo = &b.buffer;
        else
            w.pImageInfo = &b.image;
    }
    if (count > 0)
        device_.context().cmdPushDescriptorSet(cmd_, p.bindPoint, p.layout, 0, count, writes.data());
}

void VulkanCommandList::draw(uint32_t vertexCount, uint32_t instanceCount, uint32_t firstVertex,
                             uint32_t firstInstance) {
    requirePass(true, "draw");
    if (!graphics_) throw Error("draw without a graphics pipeline");
    const VulkanPipeline& p = device_.graphicsPipelines.get(graphics_);
    beforeDraw(p);
    pushBindings(p);
    noteDrawAccesses(p);
    // Split point lists (see pointChunk in VkPipelines.cpp) keep their order only with one
    // instance: instances are the outer loop of a draw.
    if (p.pointChunk == 0 || instanceCount != 1) {
        vkCmdDraw(cmd_, vertexCount, instanceCount, firstVertex, firstInstance);
        ++counts_.draws;
        countStage(pipelineBarrierCalls());
        return;
    }
    for (uint32_t done = 0; done < vertexCount; done += p.pointChunk) {
        vkCmdDraw(cmd_, std::min(p.pointChunk, vertexCount - done), 1, firstVertex + done, firstInstance);
        ++counts_.draws;
        countStage(pipelineBarrierCalls());
    }
}

void VulkanCommandList::drawIndexed(uint32_t indexCount, uint32_t instanceCount, uint32_t firstIndex,
                                    int32_t vertexOffset, uint32_t firstInstance) {
    requirePass(true, "drawIndexed");
    if (!graphics_) throw Error("drawIndexed without a graphics pipeline");
    const VulkanPipeline& p = device_.graphicsPipelines.get(graphics_);
    beforeDraw(p);
    pushBindings(p);
    noteDrawAccesses(p);
    vkCmdDrawIndexed(cmd_, indexCount, instanceCount, firstIndex, vertexOffset, firstInstance);
    ++counts_.drawsIndexed;
    countStage(pipelineBarrierCalls());
}

void VulkanCommandList::drawIndexedIndirect(BufferHandle commands, uint64_t offset, uint32_t drawCount) {
    requirePass(true, "drawIndexedIndirect");
    if (!graphics_) throw Error("drawIndexedIndirect without a graphics pipeline");
    if (!device_.caps().multiDrawIndirect) throw Error("drawIndexedIndirect: no Caps::multiDrawIndirect");
    if (!indexBuffer_) throw Error("drawIndexedIndirect without an index buffer");
    if (indexOffset_ != 0) throw Error("drawIndexedIndirect: the index buffer is bound at an offset");
    const VulkanBuffer& b = device_.buffers.get(commands);
    // The CPU wrote the commands before the frame's submission, which makes them visible: no
    // barrier to track.
    if (!(b.desc.usage & kBufferIndirect) || b.desc.access != MemoryAccess::HostWrite)
        throw Error("drawIndexedIndirect: buffer '" + b.desc.debugName +
                    "' is not a HostWrite kBufferIndirect one");
    const VulkanPipeline& p = device_.graphicsPipelines.get(graphics_);
    beforeDraw(p);
    pushBindings(p);
    noteDrawAccesses(p);
    vkCmdDrawIndexedIndirect(cmd_, b.buffer, offset, drawCount, sizeof(DrawIndexedIndirectCommand));
    ++counts_.drawsIndexed;
    countStage(pipelineBarrierCalls());
}

void VulkanCommandList::dispatch(uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) {
    requirePass(false, "dispatch");
    if (!compute_) throw Error("dispatch without a compute pipeline");
    const VulkanPipeline& p = device_.computePipelines.get(compute_);
    if (passOwed_ || dispatchHazard(p)) payAll();
    device_.flushNewTextures(cmd_);
    pushBindings(p);
    vkCmdDispatch(cmd_, groupsX, groupsY, groupsZ);
    ++counts_.dispatches;
    countStage(pipelineBarrierCalls());
    // Storage writes of the dispatch become visible to every later command that touches them: at
    // once (conservative mode) or before the next one that needs it.
    noteDispatchAccesses(p);
    owed_ = true;
    if (device_.conservativeBarriers()) payOwed();
}

bool VulkanCommandList::owedHazard(uint64_t resource, bool writes) const {
    if (!owed_ || resource == 0) return false;
    if (writtenOverflow_ || (writes && readOverflow_)) return true;
    const auto in = [](const auto& set, uint32_t n, uint64_t r) {
        return std::find(set.begin(), set.begin() + n, r) != set.begin() + n;
    };
    return in(written_, writtenCount_, resource) || (writes && in(read_, readCount_, resource));
}

bool VulkanCommandList::dispatchHazard(const VulkanPipeline& p) const {
    for (const PipelineBinding& pb : p.bindings) {
        // Storage images and buffers the shader does not declare readonly may be written.
        if (owedHazard(bound_[pb.binding].resource, pb.writable)) return true;
    }
    return false;
}

void VulkanCommandList::owe(uint64_t resource, bool writes) {
    owed_ = true;
    if (resource == 0) return;
    auto& set = writes ? written_ : read_;
    uint32_t& n = writes ? writtenCount_ : readCount_;
    if (std::find(set.begin(), set.begin() + n, resource) != set.begin() + n) return;
    if (n == kMaxTracked) { // too many to track (and no barrier inside a render pass): all count
        (writes ? writtenOverflow_ : readOverflow_) = true;
        return;
    }
    set[n++] = resource;
}

void VulkanCommandList::noteDispatchAccesses(const VulkanPipeline& p) {
    for (const PipelineBinding& pb : p.bindings) {
        owe(bound_[pb.binding].resource, pb.writable);
    }
}

bool VulkanCommandList::payOwed(BarrierBatch* batch) {
    if (!owed_) return false;
    if (batch)
        batch->memory();
    else
        fullBarrier(cmd_);
    owed_ = false;
    writtenCount_ = readCount_ = 0;
    writtenOverflow_ = readOverflow_ = false;
    return true;
}

void VulkanCommandList::clearTexture(TextureHandle texture, const std::array<float, 4>& value) {
    requirePass(false, "clearTexture");
    VulkanTexture& t = device_.textures.get(texture);
    // A storage image (home GENERAL) is cleared where it is: its barrier before the clear only where
    // an owed command touched it (every other earlier command was followed by one), and after it owed
    // like a dispatch's. Any other texture moves out and back, and those moves order its clear.
    const bool inPlace = t.home == VK_IMAGE_LAYOUT_GENERAL;
    const VkImageLayout layout = inPlace ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    const uint64_t resource = uint64_t(t.image);
    {
        BarrierBatch before(cmd_);
        // The last pass's barrier, leaving this texture to its own move.
        const PassTarget self{texture, PassTarget::kAllMips};
        const bool pass = payPass(before, std::span(&self, 1));
        before.transition(t, 0, t.desc.mipLevels, layout);
        // What dispatches owe, in the same call as the move (free then).
        if (pass || !before.empty() || owedHazard(resource, true) || device_.conservativeBarriers())
            payOwed(&before);
    }
    const VkImageSubresourceRange range{t.aspect, 0, t.desc.mipLevels, 0, t.arrayLayers()};
    if (isDepthFormat(t.desc.format)) {
        const VkClearDepthStencilValue v{value[0], 0};
        vkCmdClearDepthStencilImage(cmd_, t.image, layout, &v, 1, &range);
    } else {
        VkClearColorValue v{};
        if (isIntegerFormat(t.desc.format)) {
            for (int k = 0; k < 4; ++k)
                v.uint32[k] = uint32_t(std::max(0.0f, value[k]));
        } else {
            for (int k = 0; k < 4; ++k)
                v.float32[k] = value[k];
        }
        vkCmdClearColorImage(cmd_, t.image, layout, &v, 1, &range);
    }
    owe(resource, true);
    BarrierBatch after(cmd_);
    after.transitionHome(t);
    if (!after.empty() || device_.conservativeBarriers()) payOwed(&after);
}

void VulkanCommandList::updateBuffer(BufferHandle buffer, uint64_t offset, const void* data, uint32_t size) {
    requirePass(false, "updateBuffer");
    const VulkanBuffer& b = device_.buffers.get(buffer);
    if (!data || size == 0 || size > 65536 || size % 4 != 0 || offset % 4 != 0)
        throw Error("updateBuffer '" + b.desc.debugName +
                    "': size must be 4..65536 and offset and size multiples of 4");
    if (offset + size > b.desc.size)
        throw Error("updateBuffer '" + b.desc.debugName + "': range exceeds its size");
    // Earlier reads of the old contents, and writes, finish first: only owed commands can still be
    // touching it.
    const uint64_t resource = uint64_t(b.buffer);
    if (device_.conservativeBarriers())
        fullBarrier(cmd_);
    else if (passOwed_ || owedHazard(resource, true))
        payAll();
    vkCmdUpdateBuffer(cmd_, b.buffer, offset, size, data);
    owe(resource, true);
    if (device_.conservativeBarriers()) payOwed();
}

void VulkanCommandList::copyTextures(std::span<const TextureCopy> copies) {
    requirePass(false, "copyTextures");
    validateTextureCopies(
        copies, [&](TextureHandle t) -> const TextureDesc& { return device_.textures.get(t).desc; });
    std::array<PassTarget, 2 * TextureCopy::kMaxCopies> selves;
    for (size_t i = 0; i < copies.size(); ++i) {
        selves[2 * i] = {copies[i].src, 0};
        selves[2 * i + 1] = {copies[i].dst, 0};
    }
    // Every texture moves to its transfer layout and back (the validation layer warns of a copy in
    // GENERAL), so the moves order the copies; what dispatches owe goes into the same two calls.
    {
        BarrierBatch before(cmd_);
        payPass(before, std::span(selves.data(), 2 * copies.size()));
        for (const TextureCopy& c : copies) {
            before.transition(device_.textures.get(c.src), 0, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            before.transition(device_.textures.get(c.dst), 0, 1, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        }
        payOwed(&before);
    }
    for (const TextureCopy& c : copies) {
        VulkanTexture& s = device_.textures.get(c.src);
        VulkanTexture& d = device_.textures.get(c.dst);
        VkImageCopy region{};
        region.srcSubresource = {s.aspect, 0, 0, s.arrayLayers()};
        region.dstSubresource = region.srcSubresource;
        region.extent = {s.width(0), s.height(0), s.depth(0)};
        vkCmdCopyImage(cmd_, s.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, d.image,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    }
    BarrierBatch after(cmd_);
    for (const TextureCopy& c : copies) {
        after.transitionHome(device_.textures.get(c.src));
        after.transitionHome(device_.textures.get(c.dst));
    }
}

void VulkanCommandList::writeTimestamp(uint32_t slotIndex) {
    requireFrame("writeTimestamp");
    device_.timestamps().write(cmd_, device_.frameIndex(), slotIndex);
}

void VulkanCommandList::beginMarker(const char* name) {
    requireFrame("beginMarker");
    beginLabel(name);
    ++markerDepth_;
}

void VulkanCommandList::endMarker() {
    requireFrame("endMarker");
    if (markerDepth_ == 0) throw Error("endMarker without beginMarker");
    endLabel();
    --markerDepth_;
}

} // namespace lpv::rhi::vk
