// What the frame profiler writes: a Chrome trace-event JSON (Perfetto, chrome://tracing) with CPU
// and GPU tracks, memory and budget counters; a summary as text, Markdown and CSV; and an SVG chart
// of per-frame stacked pass times against the budget line.
#pragma once

#include <array>
#include <string>

namespace lpv::engine {

class FrameProfiler;

std::string profileSummaryText(const FrameProfiler& profiler);
// A few lines for the end of a run: the steady-state frame median and the GI's against their
// budgets, the three costliest passes, memory, and where the full report is (`fullReport`, a
// path; empty: none was written).
std::string profileShortSummary(const FrameProfiler& profiler, const std::string& fullReport);
std::string profileSummaryMarkdown(const FrameProfiler& profiler);
std::string profileSummaryCsv(const FrameProfiler& profiler);
std::string profileTraceJson(const FrameProfiler& profiler);
std::string profileChartSvg(const FrameProfiler& profiler);

// The files writeProfileOutputs writes into its directory.
inline constexpr std::array<const char*, 4> kProfileOutputFiles{"trace.json", "summary.md", "summary.csv",
                                                                "frames.svg"};

// Writes trace.json, summary.md, summary.csv and frames.svg into `directory` (created if needed).
// Every file that can be written is; then throws std::runtime_error naming each file that could
// not be, with the reason.
void writeProfileOutputs(const FrameProfiler& profiler, const std::string& directory);

} // namespace lpv::engine
