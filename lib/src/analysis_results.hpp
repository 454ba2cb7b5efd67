#pragma once
// Internal: the parts of the analyze chain that the in-memory path (analysis.cpp) and the
// bounded-memory path (analysis_bounded.cpp) share, so both write the same results.json: the
// JSON of the input, the trim, each channel's curves and PSD, one dynamic-Allan window, and the
// stages after the curves (noise-term fit, filter covariances and files, compliance).

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/analysis.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/psd.hpp"

namespace sigmatau::detail {

/// results.json's header fields (tool, version, schema, created_utc, confidence).
nlohmann::json results_header(const AnalysisOptions& options);

/// The trim object before the decision ({"mode": "auto" | "none" | "fixed"}).
nlohmann::json trim_mode_json(const AnalysisOptions& options);

/// Trim of TrimMode::fixed and none [samples] (0 for none), with the reason written into `trim`.
/// Throws Error when --trim is negative.
std::int64_t requested_trim(const AnalysisOptions& options, double rate_hz, nlohmann::json& trim);

/// Throws Error when a trim of trim_samples leaves nothing of samples_in; otherwise records the
/// trim's length in `trim`.
void record_trim(std::int64_t trim_samples, std::int64_t samples_in, double rate_hz,
                 nlohmann::json& trim);

/// results.json's "input" object.
nlohmann::json input_json(const AnalysisInput& input, std::int64_t samples,
                          std::int64_t samples_in, const nlohmann::json& trim);

/// One channel's entry in results.json's "channels" (the PSD is added by add_psd).
nlohmann::json channel_json(const AnalysisChannel& channel, const std::string& input_unit,
                            const std::vector<AllanCurve>& curves);

/// The outlier check of one channel as read (SI values): on the values of rate and increment
/// logs, on the differences of consecutive values of phase logs (a rate spike is a phase step);
/// values in the message in `input_unit` ("" = SI, unlabelled).
OutlierChecker outlier_checker(const std::string& channel, DataKind kind,
                               const std::string& input_unit);

/// Adds the log-binned PSD and its noise density to a channel entry.
void add_psd(nlohmann::json& entry, const PsdCurve& psd, const AnalysisChannel& channel,
             const AnalysisOptions& options);

/// Length of each dynamic-Allan window [samples] for a channel of `samples` samples:
/// K half-overlapping windows of 2 M / (K + 1), the w-th starting at w x length / 2.
std::int64_t dynamic_window_length(std::int64_t samples, int windows);
/// Windows shorter than this are not computed (no OADEV point worth drawing) [samples].
inline constexpr std::int64_t kMinDynamicWindow = 16;

/// One dynamic-Allan window: OADEV at the default (octave) factors of `window`, which starts at
/// sample `start` and spans `length` samples.
nlohmann::json dynamic_window_json(const PhaseSeries& window, std::int64_t start,
                                   std::int64_t length, double rate_hz);

/// The stages after the curves, into `results`: the noise-term fit of every sensor channel on
/// its first curve, filter covariances and files at each rate (into output.filter_files), the
/// data-sheet compliance and its plot lines; then the warnings, and output.results_json.
/// `channels` gives names and roles (values are not used); `samples` is the analysed length.
void finish_results(nlohmann::json& results, nlohmann::json& warnings,
                    const std::vector<AnalysisChannel>& channels,
                    const std::vector<std::vector<AllanCurve>>& curves, std::int64_t samples,
                    DataKind kind, double rate_hz, const AnalysisOptions& options,
                    AnalysisOutput& output);

}  // namespace sigmatau::detail
