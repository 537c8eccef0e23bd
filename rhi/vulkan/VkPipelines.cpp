// Pipeline creation: reflected push-descriptor layout, shader modules, fixed-function state, and
// dynamic rendering formats (no render pass objects).
#include "VkPipelines.h"

#include "VkCheck.h"
#include "VkFormats.h"
#include "VkReflection.h"

#include "../src/DescValidation.h"

#include <algorithm>
#include <array>
#include <span>
#include <string>

namespace lpv::rhi::vk {
namespace {

VkShaderModule createModule(const VulkanContext& ctx, const ShaderBinary& shader) {
    VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
    info.codeSize = shader.spirv.size_bytes();
    info.pCode = shader.spirv.data();
    VkShaderModule module = VK_NULL_HANDLE;
    vkCheck(vkCreateShaderModule(ctx.device, &info, nullptr, &module), "vkCreateShaderModule");
    ctx.name(VK_OBJECT_TYPE_SHADER_MODULE, module, std::string(shader.name));
    return module;
}

// Shader modules live only as long as pipeline creation needs them.
struct Modules {
    const VulkanContext& ctx;
    std::array<VkShaderModule, 2> list{};
    ~Modules() {
        for (VkShaderModule m : list)
            if (m) vkDestroyShaderModule(ctx.device, m, nullptr);
    }
};

// Whether a shader declares the DrawParameters capability (gl_BaseVertex, gl_BaseInstance,
// gl_DrawID): it would tell the chunks of a split draw apart. Capabilities come first in a module.
bool usesDrawParameters(std::span<const uint32_t> spirv) {
    constexpr uint32_t kOpCapability = 17, kCapabilityDrawParameters = 4427;
    for (size_t i = 5; i + 1 < spirv.size() && (spirv[i] & 0xffffu) == kOpCapability; i += spirv[i] >> 16)
        if (spirv[i + 1] == kCapabilityDrawParameters) return true;
    return false;
}

// Points per draw for a point-list pipeline on a CPU device (0: draws go out whole). lavapipe
// (Mesa 22.3) clips Vulkan points as squares, so a point outside the clip volume is not dropped
// but goes on through its draw module's primitive pipeline, and each flush of that pipeline's
// vertex buffer (every few dozen points) walks every vertex of the batch, up to 4096: a draw of n
// points costs about n * 4096 / 30 steps where GL drops the points first. That was most of
// gi/occlusion and gi/inject, whose points outside the slice drawn sit at x = y = -4. Chunks of
// 512 points cut the walk by 8; a vkCmdDraw per chunk costs less than it saves (128 to 1024
// measured alike, 2048 clearly worse).
uint32_t pointChunk(const VulkanContext& ctx, const GraphicsPipelineDesc& desc) {
    constexpr uint32_t kCpuPointChunk = 512;
    if (desc.topology != PrimitiveTopology::PointList) return 0;
    if (ctx.properties.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU) return 0;
    return usesDrawParameters(desc.vertex->spirv) ? 0 : kCpuPointChunk;
}

// Fills the layout objects of `p` from the reflected bindings; destroyPipeline cleans up on failure.
void createLayout(const VulkanContext& ctx, VulkanPipeline& p,
                  std::vector<VkDescriptorSetLayoutBinding>& bindings,
                  const std::vector<ShaderBinding>& merged) {
    std::sort(bindings.begin(), bindings.end(),
              [](const auto& a, const auto& b) { return a.binding < b.binding; });
    if (bindings.size() > ctx.maxPushDescriptors)
        throw Error("pipeline '" + p.name + "' declares " + std::to_string(bindings.size()) +
                    " bindings; this device pushes at most " + std::to_string(ctx.maxPushDescriptors));
    for (const auto& b : bindings) {
        bool writable = false;
        for (const ShaderBinding& m : merged)
            if (m.binding == b.binding) writable = m.writable;
        p.bindings.push_back({b.binding, b.descriptorType, writable});
    }

    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
    setInfo.bindingCount = uint32_t(bindings.size());
    setInfo.pBindings = bindings.data();
    vkCheck(vkCreateDescriptorSetLayout(ctx.device, &setInfo, nullptr, &p.setLayout),
            "vkCreateDescriptorSetLayout");
    ctx.name(VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, p.setLayout, p.name + " bindings");

    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &p.setLayout;
    vkCheck(vkCreatePipelineLayout(ctx.device, &layoutInfo, nullptr, &p.layout), "vkCreatePipelineLayout");
    ctx.name(VK_OBJECT_TYPE_PIPELINE_LAYOUT, p.layout, p.name + " layout");
}

VkPipelineColorBlendAttachmentState toVkBlend(const BlendState& b) {
    VkPipelineColorBlendAttachmentState s{};
    s.blendEnable = b.enabled ? VK_TRUE : VK_FALSE;
    s.srcColorBlendFactor = toVkBlendFactor(b.srcColor);
    s.dstColorBlendFactor = toVkBlendFactor(b.dstColor);
    s.colorBlendOp = toVkBlendOp(b.colorOp);
    s.srcAlphaBlendFactor = toVkBlendFactor(b.srcAlpha);
    s.dstAlphaBlendFactor = toVkBlendFactor(b.dstAlpha);
    s.alphaBlendOp = toVkBlendOp(b.alphaOp);
    s.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                       VK_COLOR_COMPONENT_A_BIT;
    return s;
}

} // namespace

void destroyPipeline(VkDevice device, VulkanPipeline& p) {
    if (p.pipeline) vkDestroyPipeline(device, p.pipeline, nullptr);
    if (p.layout) vkDestroyPipelineLayout(device, p.layout, nullptr);
    if (p.setLayout) vkDestroyDescriptorSetLayout(device, p.setLayout, nullptr);
    p.pipeline = VK_NULL_HANDLE;
    p.layout = VK_NULL_HANDLE;
    p.setLayout = VK_NULL_HANDLE;
}

VulkanPipeline buildGraphicsPipeline(const VulkanContext& ctx, const Caps& caps,
                                     const GraphicsPipelineDesc& desc) {
    if (!desc.vertex) throw Error("graphics pipeline '" + desc.debugName + "': no vertex shader");
    if (desc.vertex->stage != ShaderStage::Vertex)
        throw Error("graphics pipeline '" + desc.debugName + "': '" + std::string(desc.vertex->name) +
                    "' is not a vertex shader");
    if (desc.fragment && desc.fragment->stage != ShaderStage::Fragment)
        throw Error("graphics pipeline '" + desc.debugName + "': '" + std::string(desc.fragment->name) +
                    "' is not a fragment shader");
    if (desc.colorFormats.size() > RenderPassDesc::kMaxColorTargets)
        throw Error("graphics pipeline '" + desc.debugName + "': more than 8 color targets");
    validateStencilState(desc);
    if (!desc.blend.empty() && desc.blend.size() != 1 && desc.blend.size() != desc.colorFormats.size())
        throw Error("graphics pipeline '" + desc.debugName +
                    "': blend needs one entry or one per color target");

    VulkanPipeline p;
    p.name = desc.debugName;
    p.bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    p.pointChunk = pointChunk(ctx, desc);
    try {
        std::vector<VkDescriptorSetLayoutBinding> bindings;
        std::vector<ShaderBinding> merged;
        reflectBindings(*desc.vertex, VK_SHADER_STAGE_VERTEX_BIT, caps, bindings, merged);
        if (desc.fragment)
            reflectBindings(*desc.fragment, VK_SHADER_STAGE_FRAGMENT_BIT, caps, bindings, merged);
        createLayout(ctx, p, bindings, merged);

        Modules modules{ctx};
        modules.list[0] = createModule(ctx, *desc.vertex);
        if (desc.fragment) modules.list[1] = createModule(ctx, *desc.fragment);
        VkPipelineShaderStageCreateInfo stages[2]{};
        stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
        stages[0].module = modules.list[0];
        stages[0].pName = "main";
        stages[1] = stages[0];
        stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
        stages[1].module = modules.list[1];

        std::vector<VkVertexInputBindingDescription> vertexBindings;
        for (uint32_t i = 0; i < desc.vertexBuffers.size(); ++i)
            vertexBindings.push_back({i, desc.vertexBuffers[i].stride,
                                      desc.vertexBuffers[i].perInstance ? VK_VERTEX_INPUT_RATE_INSTANCE
                                                                        : VK_VERTEX_INPUT_RATE_VERTEX});
        std::vector<VkVertexInputAttributeDescription> attributes;
        for (const VertexAttribute& a : desc.attributes) {
            if (a.bufferSlot >= desc.vertexBuffers.size())
                throw Error("graphics pipeline '" + desc.debugName + "': attribute " +
                            std::to_string(a.location) + " uses vertex buffer slot " +
                            std::to_string(a.bufferSlot) + " with no layout");
            attributes.push_back({a.location, a.bufferSlot, toVkFormat(a.format), a.offset});
        }
        VkPipelineVertexInputStateCreateInfo vertexInput{
            VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        vertexInput.vertexBindingDescriptionCount = uint32_t(vertexBindings.size());
        vertexInput.pVertexBindingDescriptions = vertexBindings.data();
        vertexInput.vertexAttributeDescriptionCount = uint32_t(attributes.size());
        vertexInput.pVertexAttributeDescriptions = attributes.data();

        VkPipelineInputAssemblyStateCreateInfo assembly{
            VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        assembly.topology = toVkTopology(desc.topology);

        VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;

        VkPipelineRasterizationStateCreateInfo raster{
            VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = toVkCull(desc.cull);
        // Vulkan's convention, as the RHI's: winding is judged in framebuffer space (y down).
        raster.frontFace = desc.frontFace == FrontFace::CounterClockwise ? VK_FRONT_FACE_COUNTER_CLOCKWISE
                                                                         : VK_FRONT_FACE_CLOCKWISE;
        raster.depthBiasEnable =
            (desc.depthBiasConstant != 0.0f || desc.depthBiasSlope != 0.0f) ? VK_TRUE : VK_FALSE;
        raster.depthBiasConstantFactor = desc.depthBiasConstant;
        raster.depthBiasSlopeFactor = desc.depthBiasSlope;
        raster.lineWidth = 1.0f;

        VkPipelineMultisampleStateCreateInfo multisample{
            VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

        VkPipelineDepthStencilStateCreateInfo depth{
            VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
        depth.depthTestEnable = desc.depthTest ? VK_TRUE : VK_FALSE;
        depth.depthWriteEnable = desc.depthWrite ? VK_TRUE : VK_FALSE;
        depth.depthCompareOp = toVkCompare(desc.depthCompare);
        if (desc.stencil.enabled) {
            const StencilState& s = desc.stencil;
            depth.stencilTestEnable = VK_TRUE;
            depth.front.failOp = VK_STENCIL_OP_KEEP;
            depth.front.depthFailOp = VK_STENCIL_OP_KEEP;
            depth.front.passOp = s.pass == StencilOp::Replace ? VK_STENCIL_OP_REPLACE : VK_STENCIL_OP_KEEP;
            depth.front.compareOp = toVkCompare(s.compare);
            depth.front.compareMask = s.readMask;
            depth.front.writeMask = s.writeMask;
            depth.front.reference = s.reference;
            depth.back = depth.front;
        }

        std::array<VkPipelineColorBlendAttachmentState, RenderPassDesc::kMaxColorTargets> blends{};
        std::array<VkFormat, RenderPassDesc::kMaxColorTargets> colorFormats{};
        for (size_t i = 0; i < desc.colorFormats.size(); ++i) {
            const BlendState b =
                desc.blend.empty() ? BlendState::opaque() : desc.blend[desc.blend.size() == 1 ? 0 : i];
            blends[i] = toVkBlend(b);
            colorFormats[i] = toVkFormat(desc.colorFormats[i]);
        }
        VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        blend.attachmentCount = uint32_t(desc.colorFormats.size());
        blend.pAttachments = blends.data();

        const VkDynamicState dynamicStates[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
        dynamic.dynamicStateCount = 2;
        dynamic.pDynamicStates = dynamicStates;

        VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
        rendering.colorAttachmentCount = uint32_t(desc.colorFormats.size());
        rendering.pColorAttachmentFormats = colorFormats.data();
        rendering.depthAttachmentFormat = toVkFormat(desc.depthFormat);
        if (hasStencil(desc.depthFormat)) rendering.stencilAttachmentFormat = rendering.depthAttachmentFormat;

        VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
        info.stageCount = desc.fragment ? 2 : 1;
        info.pStages = stages;
        info.pVertexInputState = &vertexInput;
        info.pInputAssemblyState = &assembly;
        info.pViewportState = &viewport;
        info.pRasterizationState = &raster;
        info.pMultisampleState = &multisample;
        info.pDepthStencilState = &depth;
        info.pColorBlendState = &blend;
        info.pDynamicState = &dynamic;
        info.layout = p.layout;
        vkCheck(vkCreateGraphicsPipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline),
                "vkCreateGraphicsPipelines");
        ctx.name(VK_OBJECT_TYPE_PIPELINE, p.pipeline, p.name);
    } catch (...) {
        destroyPipeline(ctx.device, p);
        throw;
    }
    return p;
}

VulkanPipeline buildComputePipeline(const VulkanContext& ctx, const Caps& caps,
                                    const ComputePipelineDesc& desc) {
    if (!desc.compute) throw Error("compute pipeline '" + desc.debugName + "': no compute shader");
    if (desc.compute->stage != ShaderStage::Compute)
        throw Error("compute pipeline '" + desc.debugName + "': '" + std::string(desc.compute->name) +
                    "' is not a compute shader");
    VulkanPipeline p;
    p.name = desc.debugName;
    p.bindPoint = VK_PIPELINE_BIND_POINT_COMPUTE;
    try {
        std::vector<VkDescriptorSetLayoutBinding> bindings;
        std::vector<ShaderBinding> merged;
        reflectBindings(*desc.compute, VK_SHADER_STAGE_COMPUTE_BIT, caps, bindings, merged);
        createLayout(ctx, p, bindings, merged);
        Modules modules{ctx};
        modules.list[0] = createModule(ctx, *desc.compute);
        VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
        info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
        info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
        info.stage.module = modules.list[0];
        info.stage.pName = "main";
        info.layout = p.layout;
        vkCheck(vkCreateComputePipelines(ctx.device, VK_NULL_HANDLE, 1, &info, nullptr, &p.pipeline),
                "vkCreateComputePipelines");
        ctx.name(VK_OBJECT_TYPE_PIPELINE, p.pipeline, p.name);
    } catch (...) {
        destroyPipeline(ctx.device, p);
        throw;
    }
    return p;
}

} // namespace lpv::rhi::vk
