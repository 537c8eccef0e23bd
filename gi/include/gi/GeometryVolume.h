// The geometry volume (GV) of the occlusion pass: surfels from the lights' views (every VPL is the
// RSM block it clusters: the sun's, and the spot and point lights' with an RSM) and from the
// camera's depth buffer (a grid of G-buffer samples) are added
// into a volume whose cells are centred on the LPV's cell corners, then turned into the
// transmittance of every LPV cell face that propagation multiplies its flux by (fuzzy blocking,
// Kaplanyan & Dachsbacher 2010). See gv_common.glsl for what a cell holds.
#pragma once

#include "gi/AnalyticLight.h"
#include "gi/LpvReference.h"
#include "rhi/Device.h"

#include <glm/mat4x4.hpp>

#include <span>
#include <vector>

namespace lpv::gi {

// The surfels of a spot's or point light's (perspective) RSM: its VPLs, and what gives a VPL its
// area: the light's position, the RSM's axis and a VPL's texel block's solid angle on that axis;
// and what gives it its albedo (its flux over what a white block would reflect): the light's
// intensity, cone (about the RSM's axis) and range, as the RSM lit it (rsm_spot.frag).
struct PointLightSurfels {
    rhi::BufferHandle vpls;
    uint32_t count = 0;
    glm::vec3 position{0.0f};
    glm::vec3 axis{0.0f, -1.0f, 0.0f};
    float vplSolidAngle = 0.0f; // sr
    AnalyticLight light{};      // unscaled (gi.intensity 1); dark: the surfels give no albedo
};

struct GeometrySources {
    rhi::BufferHandle vpls; // the frame's VPLs (LightPropagationVolume's layout)
    uint32_t vplCount = 0;
    float vplArea = 0.0f; // RSM area per VPL across the light (m^2)
    glm::vec3 lightDirection{0.0f, -1.0f, 0.0f};
    rhi::TextureHandle depth;  // camera depth (D32F); none: light surfels only
    rhi::TextureHandle normal; // camera world normals
    rhi::TextureHandle albedo; // camera albedo (G-buffer, sRGB); with depth
    // The flux an RSM texel of albedo 1 reflects (sun irradiance x texel area): a VPL's albedo is
    // its flux over this times its texel count (for multiple bounces).
    glm::vec3 whiteTexelFlux{0.0f};
    glm::mat4 viewProjection{1.0f}; // the camera's, with depth
    glm::mat4 invViewProjection{1.0f};
    glm::vec3 cameraPosition{0.0f};
    // Spot and point lights with an RSM: their surfels block too (coverage only, no albedo).
    std::span<const PointLightSurfels> pointLights;
    // With depth, for a coarse cascade: each camera sample adds the area of surface it stands for
    // (gv_camera_areas.comp) instead of marking its cell as holding a surface, as the finest
    // cascade's do (gv_camera_marks.comp). Needs a volume made with cameraAreas.
    bool cameraAreas = false;
    // With a volume made with keepAlbedo: gather the surfels' albedo (surfelAlbedo()) in this pass.
    // Only a cascade that multiple bounces reflect in reads it.
    bool surfelAlbedo = true;
};

class GeometryVolume {
public:
    // Camera samples per row of the depth buffer (rows follow its aspect).
    static constexpr uint32_t kCameraSamplesPerRow = 160;
    // Points each camera sample marks in the finest cascade (gv_camera_marks.comp): itself, the point
    // half way to each of two neighbours on its surface, and the edges of its footprint toward the
    // four neighbours.
    static constexpr uint32_t kCameraPointsPerSample = 7;

    // keepAlbedo: also gather the surfels' albedo (surfelAlbedo()), which only multiple bounces
    // read (gi.bounces > 1); it costs 8 bytes per GV cell and 4 per LPV cell (GiBudget.cpp), more
    // than the console setup's budget has left.
    // faceSlots: how many face transmittance volumes it keeps, one per cascade (record()'s slot),
    // so that the lookup can read every cascade's after all were built.
    // cameraAreas: keep the volume the coarse cascades' camera samples add their areas into
    // (GeometrySources::cameraAreas; 12 bytes per GV cell).
    // scratchPerSlot: each face slot gets its own coverage volumes too, so that recordTogether can
    // build every slot's at once (gi.cascades_together).
    GeometryVolume(rhi::Device& device, uint32_t lpvSize, bool keepAlbedo, uint32_t faceSlots = 1,
                   bool cameraAreas = false, bool scratchPerSlot = false);
    ~GeometryVolume();
    GeometryVolume(const GeometryVolume&) = delete;
    GeometryVolume& operator=(const GeometryVolume&) = delete;

    // Clears and refills the volume for `grid` (the LPV's placement), then computes the face
    // transmittance into face slot `slot`.
    void record(rhi::CommandList& cmd, const VolumeGrid& grid, const GeometrySources& sources,
                uint32_t slot = 0);
    // One build of recordTogether: what record() takes.
    struct Build {
        VolumeGrid grid;
        const GeometrySources* sources = nullptr;
        uint32_t slot = 0;
    };
    // Several builds (up to 4, distinct slots of a volume made with scratchPerSlot, at most one
    // gathering albedo) recorded phase by phase, each phase of all of them before the next: the
    // builds do not depend on each other, so each phase is one stage of the GPU's dependent chain.
    // The last build's slot is the one faceTransmittance() then gives.
    void recordTogether(rhi::CommandList& cmd, std::span<const Build> builds);

    // Per LPV cell: transmittance of its -x, -y, -z faces (RGBA8, xyz), of the last record()
    // (propagation and bounces read it), or of a slot's (the lookup, for each cascade).
    rhi::TextureHandle faceTransmittance() const { return faces_[lastSlot_]; }
    rhi::TextureHandle faceTransmittance(uint32_t slot) const { return faces_.at(slot); }
    uint32_t faceSlots() const { return uint32_t(faces_.size()); }
    // Per GV cell (lpvSize + 1 per axis): projected coverage along x, y, z from the light's
    // surfels (RGBA8), and the finest cascade's camera marks: per axis the largest |n| its samples
    // saw there (R32UI, packUnorm4x8 of x, y, z, as glm::unpackUnorm4x8 reads it; the top byte
    // holds its real gaps, bit `axis` set where the camera sees through it, gv_gaps.comp): the
    // last build's coverage and the last marks taken.
    rhi::TextureHandle lightCoverage() const { return scratchOf(lastSlot_).coverage; }
    rhi::TextureHandle cameraMarks() const { return scratchOf(marksSlot_).cameraMarks; }
    // Per GV cell g and axis a, texel (3 g.x + a, g.y, g.z): a coarse cascade's camera coverage
    // along a (R32UI, fixed point: gv_camera_areas.glsl), the last taken. None unless made with
    // cameraAreas.
    rhi::TextureHandle cameraAreas() const { return scratchOf(areasSlot_).cameraAreas; }
    // Per LPV cell: the mean albedo of the surfels at its corners (RGBA8, rgb; a: 1 where any),
    // what multiple bounces reflect with. None unless made with keepAlbedo.
    rhi::TextureHandle surfelAlbedo() const { return albedo_; }
    // The camera samples a depth buffer of width x height gives (kCameraSamplesPerRow a row).
    static uint32_t cameraSampleCount(uint32_t width, uint32_t height);

private:
    struct InjectUniforms;
    // Counts, then adds, the albedo of the camera's samples (cameraSamples of them; 0: none) and the
    // sun's VPLs into albedoSums_ (gv_albedo_sums_body.glsl). Whether any surfel was added.
    bool addAlbedoSums(rhi::CommandList& cmd, const InjectUniforms& base, const GeometrySources& src,
                       uint32_t cameraSamples);

    // The coverage a build fills before its faces pass reads it: one set, or one per face slot.
    struct Scratch {
        rhi::TextureHandle coverage, cameraMarks;
        rhi::TextureHandle cameraAreas; // made with cameraAreas
    };
    const Scratch& scratchOf(uint32_t slot) const { return scratch_[scratch_.size() > 1 ? slot : 0]; }
    // A build's choices, made before its phases (recordTogether).
    struct Plan {
        bool areas = false, marks = false, albedo = false;
        uint32_t cameraSamples = 0;
    };

    rhi::Device& device_;
    uint32_t lpvSize_;
    bool layered_; // points in one layered draw (rhi Caps::vertexShaderLayer)
    std::vector<Scratch> scratch_;
    std::vector<rhi::TextureHandle> faces_;
    uint32_t lastSlot_ = 0;
    // The last builds that took the camera's marks and its areas: whose the accessors give.
    uint32_t marksSlot_ = 0, areasSlot_ = 0;
    rhi::GraphicsPipelineHandle vplPipeline_, pointLightPipeline_;
    rhi::ComputePipelineHandle cameraMarksPipeline_, gapsPipeline_, facesPipeline_;
    // With keepAlbedo: per GV cell (texels 2 g.x and 2 g.x + 1) its surfels' mean albedo in fixed
    // point and their count (R32UI, gv_albedo_sums_body.glsl), the passes that add the camera's
    // samples', the sun's VPLs' or both, per LPV cell the mean (albedo_), and the faces pass that
    // also takes that mean.
    rhi::TextureHandle albedoSums_, albedo_;
    // [pass: 0 counts, 1 adds][the camera's samples, the sun's VPLs, both]
    rhi::ComputePipelineHandle albedoPipelines_[2][4]; // [pass][camera, VPLs, both, a light's]
    rhi::ComputePipelineHandle facesAlbedoPipeline_;
    // With cameraAreas (Scratch::cameraAreas): the pass that fills it, and the faces pass that reads it.
    bool cameraAreas_ = false;
    rhi::ComputePipelineHandle cameraAreasPipeline_, facesAreasPipeline_, facesAreasAlbedoPipeline_;
    rhi::SamplerHandle pointSampler_;
};

} // namespace lpv::gi
