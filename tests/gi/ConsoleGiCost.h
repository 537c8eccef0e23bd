// The predicted console cost and the memory of a cascaded GI frame, for the budget scheduler's
// tests: the stand-in for cascades, which are not written yet. Every cascade updated this frame
// draws its own RSM, clusters it into VPLs, injects and propagates (gi/GiWork.h work counts); the
// lookup runs once. Pass times come from the console cost model and add up, as in the cost
// model's calibration test (tests/gi/LpvReferenceTests.cpp).
#pragma once

#include "engine/profiler/CostModel.h"
#include "gi/FogMarch.h"
#include "gi/GiBudget.h"
#include "gi/GiScheduler.h"
#include "gi/GiWork.h"
#include "gi/LpvSettings.h"
#include "platforms/PlatformProfile.h"

#include <array>

namespace lpv::test {

struct ConsoleGiCost {
    gi::LpvSettings base;             // grid, format, VPL count shared by every cascade
    platforms::Throughput throughput; // of the console profile
    uint64_t sceneTriangles = 100000; // as in the calibration test
    uint64_t pixels = 1280 * 720;

    gi::LpvSettings settingsOf(const gi::GiLoad& load) const {
        gi::LpvSettings s = base;
        gi::applyGiLoad(load, s);
        return s;
    }
    // The passes of one cascade's update: its light half (RSM, VPLs), then its volume half
    // (injection, propagation; the further bounces in the finest gi.bounce_cascades).
    std::array<engine::WorkCounts, 2> lightPasses(const gi::GiLoad& load) const {
        const gi::LpvSettings s = settingsOf(load);
        return {gi::rsmWork(s, sceneTriangles), gi::vplClusterWork(s)};
    }
    std::array<engine::WorkCounts, 2> volumePasses(const gi::GiLoad& load) const {
        const gi::LpvSettings s = settingsOf(load);
        return {gi::injectWork(s), gi::propagateWork(s)};
    }
    // The lookup of one cascade per pixel: a synthetic load, so the tests exercise the knobs the
    // scheduler turns. (The shipped lookup samples up to two cascades per pixel, which no knob
    // changes; lpv_bench prints the console preset's prediction with it.)
    engine::WorkCounts lookupPass(const gi::GiLoad& load) const {
        gi::LpvSettings s = settingsOf(load);
        s.cascades = 1;
        return gi::lookupWork(s, pixels / (uint64_t(load.resolutionDivisor) * load.resolutionDivisor));
    }

    double passMs(const engine::WorkCounts& w) const { return engine::predictCost(w, throughput).ms; }
    double cascadeMs(const gi::GiLoad& load, uint32_t cascade, uint32_t halves) const {
        double ms = 0;
        if (halves & gi::kCascadeLight)
            for (const auto& w : lightPasses(load))
                ms += passMs(w);
        if (halves & gi::kCascadeVolume) {
            for (const auto& w : volumePasses(load))
                ms += passMs(w);
            const gi::LpvSettings s = settingsOf(load);
            if (s.bouncesIn(cascade)) ms += passMs(gi::bounceWork(s));
        }
        return ms;
    }
    // Predicted ms of GI on `frame`: the halves of cascade updates due that frame, and the lookup.
    double frameMs(const gi::GiLoad& load, uint64_t frame) const {
        double ms = passMs(lookupPass(load));
        // With fog on: its march through every cascade, at fog.resolution.
        if (load.fogSteps > 0) {
            const gi::LpvSettings s = settingsOf(load);
            const uint64_t d = load.fogResolutionDivisor;
            ms += passMs(gi::fogWork(s.fog, pixels / (d * d), true));
        }
        for (uint32_t c = 0; c < load.cascades; ++c)
            ms += cascadeMs(load, c, gi::cascadeWorkOn(load, c, frame));
        return ms;
    }
    // The worst frame of a coarse update cycle.
    double peakMs(const gi::GiLoad& load) const {
        double peak = 0;
        for (uint64_t f = 0; f < 4 * load.coarseUpdateInterval; ++f)
            peak = peak > frameMs(load, f) ? peak : frameMs(load, f);
        return peak;
    }
    // Every cascade keeps its volumes and its RSM (gi/GiBudget.h's resource plan per cascade).
    uint64_t bytes(const gi::GiLoad& load) const {
        return gi::giBytes(gi::giResources(settingsOf(load))) * load.cascades;
    }
};

// The expensive setup of the tests: 3 cascades of 32^3, 8 iterations, RSM 256, RGBA8 (the only
// format the x360 profile allows), 1024 VPLs (a 32x32 grid, so every RSM size down to 64 divides),
// every pixel looked up (gi.resolution=full), so each knob has work to take away.
inline ConsoleGiCost x360Cascades(gi::GiLoad& configured) {
    ConsoleGiCost cost;
    cost.base.gridSize = 32;
    cost.base.shFormat = gi::ShFormat::Rgba8;
    cost.base.vplCount = 1024;
    cost.base.iterations = 8;
    cost.base.rsmSize = 256;
    cost.base.resolutionDivisor = 1;
    cost.throughput = platforms::loadPlatformProfile("x360").throughput;
    configured = gi::giLoadOf(cost.base, 3);
    return cost;
}

} // namespace lpv::test
