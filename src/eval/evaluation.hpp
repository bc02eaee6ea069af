// actionstring host library — one evaluation run: what `actionstring eval`
// computes and prints, and what the Python package's Model.evaluate returns.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "eval/clip_eval.hpp"
#include "eval/online.hpp"
#include "eval/perturb.hpp"
#include "io/clip_list.hpp"
#include "io/recordings.hpp"

namespace actionstring {
namespace host {

/// Everything one evaluation run computes.
struct Evaluation {
    std::vector<LabelledClip> clips;
    bool recordings = false;           ///< The streams are whole recordings (a list with intervals).
    std::vector<ClipResults> results;  ///< The model's first, then the baselines.
    std::vector<double> frame_ns;      ///< The annotator's per-frame times, sorted.
    bool frame_spread = false;         ///< Whether they were taken with spread_work.
    bool online = false;
    OnlineReport online_report;
    /// With recordings: their unlabelled stretches of 1 s or more, each
    /// classified as a clip, and how many came out unknown (the classifier's
    /// rejection of real non-actions; label_bounds, unknown_distance).
    std::size_t no_action_stretches = 0, no_action_unknown = 0;
    /// Synthetic non-actions made from the evaluated clips (synthetic_negatives():
    /// spliced halves, and clips sped up or slowed down that land on another
    /// label than their own), and how many came out unknown.
    std::size_t synthetic_negatives = 0, synthetic_unknown = 0;
    /// How the evaluated clips and recordings were changed (Perturbation::describe(); "none").
    std::string perturbation = "none";
};

/// Evaluates a model on labelled clips, conformed to its skeleton: the
/// model's clip results, with `train` the baselines on the same split (1-NN
/// over all training strings, the same with PCA-only characters, DTW 1-NN on
/// poses), the annotator's per-frame time, and with `online` the streaming
/// figures: over `recordings` whole when given, else over the clips
/// concatenated per subject in a seeded order. `perturbation` changes the
/// evaluated clips and recordings first (each its own draws: clip i index i,
/// recording r index 2^32 + r), never the training clips.
Evaluation evaluate(const ModelView& model, std::vector<LabelledClip> clips, std::vector<LabelledClip> train,
                    std::vector<LabelledRecording> recordings, bool online, std::uint32_t seed,
                    const AnnotatorConfig& config, const Perturbation& perturbation = {});

/// The run as the JSON object `actionstring eval --json` writes.
std::string evaluation_json(const Evaluation& e, const std::string& model_name, std::uint32_t seed,
                            const AnnotatorConfig& config);

}  // namespace host
}  // namespace actionstring
