// Per-frame latency of the annotator and of each runtime stage on a real
// stream, the incremental matcher against batch recomputation, state and table
// bytes, heap allocations, and how the cost scales with the model's size.
//
//   actionstring_frame_latency [--passes N] [--json FILE] [--markdown FILE] [--no-scaling]
//
// Stream: every clip of hdm05/val.tsv joined in list order (120 Hz). Models:
// the committed example header (no GMM: bone lengths, velocity, at most 350
// representative characters; models/hdm05.config), and the paper's GMM models
// trained here on hdm05/train.tsv with models/hdm05-gmm.config's settings (the
// library's defaults), J = 20 and J = 40. One warm-up pass, then N
// timed passes (default 20); each call timed alone with the steady clock,
// whose own overhead is measured and reported (not subtracted).
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "actionstring/actionstring.hpp"
#include "model/artifact.hpp"
#include "model/header.hpp"
#include "io/stream.hpp"
#include "eval/baselines.hpp"
#include "eval/clip_eval.hpp"
#include "eval/json.hpp"
#include "eval/online.hpp"
#include "run/state.hpp"
#include "run/stream_labels.hpp"
#include "io/clip_list.hpp"
#include "io/formats.hpp"
#include "run/classify.hpp"
#include "run/encode.hpp"
#include "train/gmm_em.hpp"
#include "train/pca.hpp"
#include "train/pipeline.hpp"
#include "train/settings.hpp"
#include "actionstring_port.hpp"
#include "hdm05_model.hpp"
#include "synthetic_model.hpp"

using namespace actionstring;

// ---- heap allocations made while the runtime runs (there must be none) ----------
namespace {
volatile std::uint32_t g_sink;  // keeps timed results alive
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
    if (g_counting.load(std::memory_order_relaxed)) ++g_allocations;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

namespace {

struct Stats {
    std::size_t n = 0;
    double median = 0, p99 = 0, p999 = 0, max = 0, mean = 0;
};

Stats summarize(std::vector<std::int64_t> values) {
    Stats s;
    if (values.empty()) return s;
    std::sort(values.begin(), values.end());
    auto at = [&](double q) {
        return static_cast<double>(
            values[std::min(values.size() - 1, static_cast<std::size_t>(q * static_cast<double>(values.size())))]);
    };
    s.n = values.size();
    s.median = at(0.5);
    s.p99 = at(0.99);
    s.p999 = at(0.999);
    s.max = static_cast<double>(values.back());
    double total = 0;
    for (const auto v : values) total += static_cast<double>(v);
    s.mean = total / static_cast<double>(values.size());
    return s;
}

struct Row {
    std::string model, what;
    Stats stats;
};

struct Report {
    std::vector<Row> latency;
    std::vector<std::string> notes;
    std::ostringstream json_models;
    std::ostringstream markdown_extra;
};

template <class Time>
std::int64_t timed(Time&& call) {
    const std::int64_t begin = port::monotonic_ns();
    call();
    return port::monotonic_ns() - begin;
}

std::int64_t clock_overhead_ns() {
    std::vector<std::int64_t> gaps;
    for (int i = 0; i < 100000; ++i) gaps.push_back(timed([] {}));
    return static_cast<std::int64_t>(summarize(gaps).median);
}

std::string machine_description() {
    std::string cpu = "unknown CPU";
    std::ifstream info("/proc/cpuinfo");
    for (std::string line; std::getline(info, line);)
        if (line.rfind("model name", 0) == 0) {
            cpu = line.substr(line.find(':') + 2);
            break;
        }
    char text[512];
    std::snprintf(text, sizeof text, "%s, %u hardware threads; compiler %s", cpu.c_str(),
                  std::thread::hardware_concurrency(), __VERSION__);
    return text;
}

/// Table bytes of each part of a model.
void table_bytes(const ModelView& m, std::ostringstream& json, std::ostringstream& md, const std::string& name) {
    const std::size_t d = m.feature_dim, J = m.component_count;
    const std::size_t pose = 3u * m.pose_joint_count;
    const std::size_t normalise = m.pose_joint_count * sizeof(std::uint16_t);
    const std::size_t pca = m.has_projection() ? (pose + pose * d) * sizeof(float) : 0;
    const std::size_t gmm = (J * d + J * m.factor_size() + 2 * J) * sizeof(float);
    const std::size_t tree = m.node_count * (J * sizeof(float) + 2 * sizeof(std::int16_t) + sizeof(Character)) +
                             static_cast<std::size_t>(m.character_count) * m.character_count * sizeof(float);
    const std::size_t strings = (m.representative_count + 1u) * sizeof(std::uint32_t) +
                                m.total_representative_chars() * sizeof(Character) +
                                m.representative_count * sizeof(LabelId);
    const std::size_t votes =
        m.has_votes() ? (std::size_t{m.label_count} + (m.has_no_action_votes ? 1u : 0u)) * m.character_count * sizeof(float)
                      : 0;
    // The total is the schema's own count (every table, names and bone tables included).
    const std::size_t total = host::table_bytes(m);
    json << "\"table_bytes\": {\"normalise\": " << normalise << ", \"pca\": " << pca << ", \"gmm\": " << gmm
         << ", \"tree_and_W\": " << tree << ", \"strings\": " << strings << ", \"votes\": " << votes
         << ", \"total\": " << total << "}";
    md << "| " << name << " | " << normalise << " | " << pca << " | " << gmm << " | " << tree << " | " << strings
       << " | " << votes << " | " << total << " |\n";
}

/// Both rules: the window rule's cost is measured too.
AnnotatorConfig every_rule(const ModelView& model) {
    AnnotatorConfig config = annotator_config(model);
    config.window_rule = true;
    return config;
}

/// Everything measured on one model over the real stream.
void measure_model(const std::string& name, const ModelView& model, const host::ConcatenatedStream& stream, int passes,
                   Report& report, std::ostringstream& memory_md, std::ostringstream& tables_md) {
    host::Stateful<Annotator> annotator;
    if (annotator.init(model, every_rule(model)) != Status::ok) {
        std::fprintf(stderr, "%s: the annotator refused the model\n", name.c_str());
        std::exit(1);
    }
    const std::size_t frames = stream.frame_count();
    std::vector<std::int64_t> all, character_frames, window_frames, plain_frames;
    long allocations = 0;
    for (int pass = 0; pass <= passes; ++pass) {
        annotator->reset();
        g_allocations = 0;
        for (std::size_t f = 0; f < frames; ++f) {
            FrameResult result;
            const std::int64_t ns = timed([&] {
                g_counting.store(true, std::memory_order_relaxed);
                result = annotator->push_frame(stream.times_us[f], stream.frame(f));
                g_counting.store(false, std::memory_order_relaxed);
            });
            if (pass == 0) continue;  // warm-up
            all.push_back(ns);
            (result.characters > 0 ? character_frames : plain_frames).push_back(ns);
            if (result.windows_completed > 0) window_frames.push_back(ns);
        }
        if (pass > 0) allocations += g_allocations.load();
    }
    report.latency.push_back({name, "annotator: every frame", summarize(all)});
    report.latency.push_back({name, "annotator: frames without a character", summarize(plain_frames)});
    report.latency.push_back({name, "annotator: frames that emit a character", summarize(character_frames)});
    report.latency.push_back({name, "annotator: frames that complete a window", summarize(window_frames)});

    // The model's own settings, as a device runs it: the segmenter alone.
    host::Stateful<Annotator> own;
    if (own.init(model, annotator_config(model)) != Status::ok) {
        std::fprintf(stderr, "%s: the annotator refused the model's own settings\n", name.c_str());
        std::exit(1);
    }
    // And again with each character's work (encoder and segmenter) spread over
    // the frames until the next one (AnnotatorConfig::spread_work): the same
    // labels, a flatter frame cost.
    AnnotatorConfig spread_config = annotator_config(model);
    spread_config.spread_work = true;
    host::Stateful<Annotator> spread;
    if (spread.init(model, spread_config) != Status::ok) {
        std::fprintf(stderr, "%s: the annotator refused the model's own settings, spread\n", name.c_str());
        std::exit(1);
    }
    std::vector<std::int64_t> own_every, own_character_frames, spread_every, spread_character_frames;
    for (int pass = 0; pass <= passes; ++pass) {
        own->reset();
        spread->reset();
        for (std::size_t f = 0; f < frames; ++f) {
            FrameResult result, spread_result;
            const std::int64_t ns = timed([&] { result = own->push_frame(stream.times_us[f], stream.frame(f)); });
            const std::int64_t spread_ns =
                timed([&] { spread_result = spread->push_frame(stream.times_us[f], stream.frame(f)); });
            if (pass == 0) continue;
            own_every.push_back(ns);
            spread_every.push_back(spread_ns);
            if (result.characters > 0) own_character_frames.push_back(ns);
            if (spread_result.characters > 0) spread_character_frames.push_back(spread_ns);
        }
    }
    report.latency.push_back({name, "annotator, own settings (segmenter alone): every frame", summarize(own_every)});
    report.latency.push_back(
        {name, "annotator, own settings (segmenter alone): frames that emit a character", summarize(own_character_frames)});
    report.latency.push_back({name, "annotator, own settings, work spread: every frame", summarize(spread_every)});
    report.latency.push_back({name, "annotator, own settings, work spread: frames that emit a character",
                              summarize(spread_character_frames)});

    // Stages, each called alone on every frame of the stream (the velocity,
    // GMM and projection stages only where the model has them).
    std::vector<std::int64_t> normalise_ns, velocity_ns, project_ns, posterior_ns, descent_ns;
    std::vector<float> pose_buffer(model.input_dim()), feature_buffer(model.feature_dim),
        posterior_buffer(model.component_count), scratch_buffer(gmm_scratch_floats(model)),
        skeleton_buffer(3u * model.joint_count);
    float* const pose = pose_buffer.data();
    float* const feature = feature_buffer.data();
    float* const posterior = posterior_buffer.data();
    float* const scratch = scratch_buffer.data();
    float* const skeleton_data = skeleton_buffer.data();
    // The encoder's descent: on GMM posteriors the sparse one, with its node norms.
    std::vector<float> norms(tree_norm_floats(model));
    std::vector<std::uint16_t> nonzero(model.tree_dim());
    tree_node_norms(model, norms.data());
    host::Stateful<MotionRing> motion;
    if (motion.init(model) != Status::ok) {
        std::fprintf(stderr, "%s: the velocity ring refused the model\n", name.c_str());
        std::exit(1);
    }
    for (int pass = 0; pass <= passes; ++pass) {
        motion->reset();
        for (std::size_t f = 0; f < frames; ++f) {
            Status status = Status::ok;
            const std::int64_t a = timed([&] { status = normalize_pose(model, stream.frame(f), pose, skeleton_data); });
            if (status != Status::ok) continue;
            std::int64_t v = 0;
            if (model.has_motion()) v = timed([&] { motion->update(model, stream.times_us[f], pose); });
            const float* input = pose;
            std::int64_t b = 0;
            if (model.has_projection()) {
                b = timed([&] { project_pose(model, pose, feature); });
                input = feature;
            }
            std::int64_t c = 0;
            if (model.has_gmm()) {
                c = timed([&] { status = gmm_posterior(model, input, posterior, scratch); });
                if (status != Status::ok) continue;
                input = posterior;
            }
            Character character = 0;
            const std::int64_t d = timed([&] {
                character = model.has_gmm() ? descend_tree_sparse(model, input, norms.data(), nonzero.data())
                                            : descend_tree(model, input);
            });
            g_sink = character;
            if (pass == 0) continue;
            normalise_ns.push_back(a);
            if (model.has_motion()) velocity_ns.push_back(v);
            if (model.has_projection()) project_ns.push_back(b);
            if (model.has_gmm()) posterior_ns.push_back(c);
            descent_ns.push_back(d);
        }
    }
    report.latency.push_back({name, "stage: normalise", summarize(normalise_ns)});
    if (!velocity_ns.empty()) report.latency.push_back({name, "stage: velocity", summarize(velocity_ns)});
    if (!project_ns.empty()) report.latency.push_back({name, "stage: project (PCA)", summarize(project_ns)});
    if (!posterior_ns.empty()) report.latency.push_back({name, "stage: GMM posterior", summarize(posterior_ns)});
    report.latency.push_back({name, "stage: tree descent", summarize(descent_ns)});

    // The stream's action string, as the encoder emits it.
    host::Stateful<StringEncoder> encoder;
    encoder.init(model, EncoderConfig{});
    std::vector<Character> string;
    std::vector<float> features;  // feature_dim per character, for the exemplars
    const std::size_t d = model.feature_dim;
    for (std::size_t f = 0; f < frames; ++f) {
        const EncodedFrame e = encoder->push_frame(stream.times_us[f], stream.frame(f));
        if (!e.accepted()) continue;
        string.insert(string.end(), e.from_previous, e.previous);
        string.insert(string.end(), e.from_current, e.current);
        for (std::size_t i = 0; i < e.from_previous; ++i)
            features.insert(features.end(), e.previous_feature, e.previous_feature + d);
        for (std::size_t i = 0; i < e.from_current; ++i)
            features.insert(features.end(), e.current_feature, e.current_feature + d);
    }
    // Exemplars: each character's distances to every label's nearest centre
    // (what clip classification sums, and the segmenter weighs when set to).
    if (model.has_exemplars()) {
        std::vector<float> distances(model.label_count);
        std::vector<std::int64_t> exemplar_ns;
        for (int pass = 0; pass <= passes; ++pass)
            for (std::size_t i = 0; i < string.size(); ++i) {
                const std::int64_t ns = timed([&] { exemplar_distances(model, &features[i * d], distances.data()); });
                g_sink = static_cast<std::uint32_t>(distances[0] > 1.0f);
                if (pass > 0) exemplar_ns.push_back(ns);
            }
        char what[96];
        std::snprintf(what, sizeof what, "stage: exemplar distances (per character, %u centres)",
                      static_cast<unsigned>(model.exemplar_count));
        report.latency.push_back({name, what, summarize(exemplar_ns)});
    }

    // Matcher: incremental per character, against the batch DP over each completed window.
    host::Stateful<WindowMatcher> matcher;
    matcher.init(model);
    const std::size_t R = model.representative_count;
    std::vector<std::int64_t> push_ns, classify_ns, batch_window_ns;
    std::int64_t incremental_total = 0, batch_total = 0;
    std::size_t windows = 0, identical = 0, compared = 0;
    std::vector<detail::Cell> workspace;
    std::vector<float> batch(R);
    for (int pass = 0; pass <= passes; ++pass) {
        matcher->reset();
        for (std::size_t i = 0; i < string.size(); ++i) {
            bool completed = false;
            const std::int64_t ns = timed([&] { completed = matcher->push(string[i]); });
            if (pass > 0) {
                push_ns.push_back(ns);
                incremental_total += ns;
            }
            if (!completed) continue;
            Classification label;
            const std::int64_t c = timed(
                [&] { label = classify_distances(model, matcher->completed_distances()); });
            g_sink = label.label;
            const std::size_t start = static_cast<std::size_t>(matcher->completed_window_start());
            const std::size_t length = i + 1 - start;
            const std::int64_t b = timed([&] {
                for (std::size_t r = 0; r < R; ++r) {
                    const std::size_t rep_length = model.representative_length(r);
                    workspace.resize(string_distance_cells(length, rep_length));
                    string_distance(string.data() + start, length,
                                    model.representative_chars + model.representative_offsets[r], rep_length,
                                    character_weights(model), MatchOptions{model.variant, model.normalization},
                                    workspace.data(), &batch[r]);
                }
            });
            if (pass == 0) continue;
            ++windows;
            classify_ns.push_back(c);
            batch_window_ns.push_back(b);
            batch_total += b;
            for (std::size_t r = 0; r < R; ++r, ++compared)
                identical += std::memcmp(&batch[r], matcher->completed_distances() + r, sizeof(float)) == 0;
        }
    }
    // Segmenter: the online rule's update per character on the same string.
    host::Stateful<ActionSegmenter> segmenter;
    std::vector<std::int64_t> segment_ns;
    if (segmenter.init(model, segmenter_config(model)) == Status::ok) {
        for (int pass = 0; pass <= passes; ++pass) {
            segmenter->reset();
            for (std::size_t i = 0; i < string.size(); ++i) {
                bool settled = false;
                const std::int64_t ns = timed([&] { settled = segmenter->push(string[i]); });
                g_sink = settled ? segmenter->settled_label() : segmenter->live_label();
                if (pass > 0) segment_ns.push_back(ns);
            }
        }
        report.latency.push_back({name, "stage: segmenter update (per character)", summarize(segment_ns)});
    }
    report.latency.push_back({name, "stage: matcher update (per character)", summarize(push_ns)});
    report.latency.push_back({name, "stage: classification (per window)", summarize(classify_ns)});
    report.latency.push_back({name, "batch DP of one whole window (all representatives)", summarize(batch_window_ns)});
    const double ratio =
        incremental_total > 0 ? static_cast<double>(batch_total) / static_cast<double>(incremental_total) : 0;
    char line[512];
    std::snprintf(line, sizeof line,
                  "%s: matching the %zu windows of the stream's %zu-character string: incremental %.3f ms, batch "
                  "recomputation of each window %.3f ms (%.1f× more); %zu of %zu distances bit-identical",
                  name.c_str(), windows / static_cast<std::size_t>(passes), string.size(),
                  static_cast<double>(incremental_total) / passes / 1e6,
                  static_cast<double>(batch_total) / passes / 1e6, ratio, identical, compared);
    report.notes.push_back(line);
    std::snprintf(line, sizeof line, "%s: heap allocations during %d timed passes of %zu frames: %ld", name.c_str(),
                  passes, frames, allocations);
    report.notes.push_back(line);

    const std::size_t annotator_bytes = Annotator::required_bytes(model, every_rule(model));
    const std::size_t segmenter_only_bytes = Annotator::required_bytes(model, annotator_config(model));
    memory_md << "| " << name << " | " << annotator_bytes << " | " << segmenter_only_bytes << " | "
              << StringEncoder::required_bytes(model) << " | " << WindowMatcher::required_bytes(model) << " | "
              << ActionSegmenter::required_bytes(model, segmenter_config(model)) << " |\n";
    std::ostringstream tables_json;
    table_bytes(model, tables_json, tables_md, name);
    if (report.json_models.tellp() > 0) report.json_models << ", ";
    report.json_models << "{\"name\": \"" << name << "\", \"components\": " << model.component_count
                       << ", \"feature_dim\": " << model.feature_dim << ", \"characters\": " << model.character_count
                       << ", \"representatives\": " << R << ", \"window_chars\": " << model.window_chars
                       << ", \"state_bytes\": {\"annotator\": " << annotator_bytes
                       << ", \"annotator_segmenter_only\": " << segmenter_only_bytes
                       << ", \"encoder\": " << StringEncoder::required_bytes(model)
                       << ", \"matcher\": " << WindowMatcher::required_bytes(model)
                       << ", \"segmenter\": " << ActionSegmenter::required_bytes(model, segmenter_config(model))
                       << "}, " << tables_json.str()
                       << ", \"incremental_vs_batch\": {\"incremental_ns\": " << incremental_total / passes
                       << ", \"batch_ns\": " << batch_total / passes << ", \"ratio\": " << ratio
                       << ", \"identical\": " << identical << ", \"compared\": " << compared
                       << "}, \"allocations\": " << allocations << "}";
}

// ---- scaling on synthetic models (cost only) ----------------------------------

struct ScalingPoint {
    std::string varied;
    bench::ModelSize size;
    Stats every, character;  // both rules (the window rule and the segmenter)
    Stats own_character;     // the model's own settings (the segmenter alone, as a device runs it)
    Stats spread_every, spread_character;  // the same with the work spread (AnnotatorConfig::spread_work)
};

// Timed passes per random model: ten give about 3,600 character frames, so a
// p99 is not the few interruptions of this shared machine.
constexpr int kScalingPasses = 10;

ScalingPoint measure_scaling(const std::string& varied, const bench::ModelSize& size) {
    host::ModelData data;
    bench::make_random_model(data, size);
    data.normalization = LengthNormalization::none;
    const ModelView model = data.view();
    host::Stateful<Annotator> annotator;
    if (annotator.init(model, every_rule(model)) != Status::ok) {
        std::fprintf(stderr, "scaling model rejected\n");
        std::exit(1);
    }
    host::Stateful<Annotator> own, spread;
    AnnotatorConfig spread_config = annotator_config(model);
    spread_config.spread_work = true;
    if (own.init(model, annotator_config(model)) != Status::ok || spread.init(model, spread_config) != Status::ok) {
        std::fprintf(stderr, "scaling model rejected\n");
        std::exit(1);
    }
    const auto frames = bench::random_walk_frames(31, 120 * 30);
    std::vector<std::int64_t> every, character, own_character, spread_every, spread_character;
    for (int pass = 0; pass <= kScalingPasses; ++pass) {
        annotator->reset();
        own->reset();
        spread->reset();
        for (std::size_t f = 0; f < frames.size(); ++f) {
            FrameResult result, spread_result;
            const std::int64_t time_us = static_cast<std::int64_t>(f) * 8333;
            const std::int64_t ns = timed([&] { result = annotator->push_frame(time_us, frames[f].data()); });
            const std::int64_t own_ns = timed([&] { result = own->push_frame(time_us, frames[f].data()); });
            const std::int64_t spread_ns =
                timed([&] { spread_result = spread->push_frame(time_us, frames[f].data()); });
            if (pass == 0) continue;
            every.push_back(ns);
            spread_every.push_back(spread_ns);
            if (result.characters > 0) character.push_back(ns), own_character.push_back(own_ns);
            if (spread_result.characters > 0) spread_character.push_back(spread_ns);
        }
    }
    return {varied,
            size,
            summarize(every),
            summarize(character),
            summarize(own_character),
            summarize(spread_every),
            summarize(spread_character)};
}

/// One pass of the committed model's annotator over the stream: the only code
/// bench/callgrind_frame.sh counts instructions in (--toggle-collect).
__attribute__((noinline)) std::uint32_t callgrind_pass(Annotator& annotator,
                                                       const host::ConcatenatedStream& stream) {
    std::uint32_t characters = 0;
    for (std::size_t f = 0; f < stream.frame_count(); ++f)
        characters += annotator.push_frame(stream.times_us[f], stream.frame(f)).characters;
    return characters;
}

}  // namespace

int main(int argc, char** argv) {
    int passes = 20;
    std::string json_path, markdown_path;
    bool scaling = true, callgrind = false;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--passes" && i + 1 < argc) passes = std::max(1, std::atoi(argv[++i]));
        else if (arg == "--json" && i + 1 < argc) json_path = argv[++i];
        else if (arg == "--markdown" && i + 1 < argc) markdown_path = argv[++i];
        else if (arg == "--no-scaling") scaling = false;
        else if (arg == "--callgrind-pass") callgrind = true;
        else {
            std::fprintf(
                stderr,
                "usage: actionstring_frame_latency [--passes N] [--json FILE] [--markdown FILE] [--no-scaling]\n"
                "       actionstring_frame_latency --callgrind-pass   (see bench/callgrind_frame.sh)\n");
            return 2;
        }
    }
    const char* env = std::getenv("ACTIONSTRING_DATA");
    const std::string data = env != nullptr ? env : std::string(ACTIONSTRING_SOURCE_DIR) + "/../shared/data";
    std::vector<host::Clip> clips;
    std::vector<host::LabelledClip> training;
    try {
        for (const auto& entry : host::read_clip_list(data + "/hdm05/val.tsv")) clips.push_back(host::read_clip(entry));
        if (!callgrind)
            for (const auto& entry : host::read_clip_list(data + "/hdm05/train.tsv"))
                training.push_back({host::read_clip(entry), entry.label, entry.subject});
    } catch (const std::exception& error) {
        std::fprintf(
            stderr,
            "actionstring_frame_latency: %s\nThe benchmark replays real HDM05 recordings: set ACTIONSTRING_DATA "
            "to the datasets folder.\n",
            error.what());
        return 1;
    }
    std::vector<host::StreamSegment> segments;
    for (const auto& clip : clips) segments.push_back({&clip, "", 0.0});
    const host::ConcatenatedStream stream = host::concatenate_stream(segments);
    if (callgrind) {
        auto storage = std::make_unique<StateBuffer<actionstring_hdm05::kAnnotatorWithWindowsBytes>>();
        auto annotator = std::make_unique<Annotator>();
        annotator->init(actionstring_hdm05::kModel, every_rule(actionstring_hdm05::kModel), storage->data(),
                        storage->size());
        const std::uint32_t characters = callgrind_pass(*annotator, stream);
        std::printf("frames %zu characters %u\n", stream.frame_count(), characters);
        return 0;
    }

    host::TrainingOptions options;  // models/hdm05-gmm.config: the library's defaults, J = 20
    const host::ModelData model20 = host::train_model(training, options, nullptr);
    options.components = 40;
    const auto train_start = port::monotonic_ns();
    host::ModelData model40 = host::train_model(training, options, nullptr);
    const double train_seconds = static_cast<double>(port::monotonic_ns() - train_start) * 1e-9;

    Report report;
    const std::int64_t overhead = clock_overhead_ns();
    std::ostringstream memory_md, tables_md;
    measure_model("committed hdm05 (no GMM)", actionstring_hdm05::kModel, stream, passes, report, memory_md, tables_md);
    measure_model("hdm05 J=20", model20.view(), stream, passes, report, memory_md, tables_md);
    measure_model("hdm05 J=40", model40.view(), stream, passes, report, memory_md, tables_md);
    {
        // The clip descriptor (descriptor.hpp), which only whole-clip classification
        // pays: hdm05-accurate.config's model (no GMM, PCA 24, its descriptor: three
        // levels over 24 coordinates, 11 labels), each validation clip's pyramid and
        // penalties timed once per pass from its characters' features.
        host::TrainingOptions accurate;
        host::ReadOptions read;
        host::read_training_config(std::string(ACTIONSTRING_SOURCE_DIR) + "/models/hdm05-accurate.config", accurate,
                                   read);
        const host::ModelData described = host::train_model(training, accurate, nullptr);
        const ModelView view = described.view();
        std::vector<std::vector<float>> features, records;
        std::vector<std::vector<Character>> strings;
        std::size_t characters = 0, longest = 0;
        for (const host::Clip& clip : clips) {
            host::EncodedClip encoded = host::encode_clip(view, clip, true, view.has_directions());
            features.push_back(std::move(encoded.features));
            records.push_back(std::move(encoded.records));
            strings.push_back(std::move(encoded.string));
            characters += strings.back().size();
            longest = std::max(longest, strings.back().size());
        }
        std::vector<float> scratch(view.descriptor_size()), penalties(view.label_count);
        std::vector<std::int64_t> per_clip;
        long allocations = 0;
        for (int pass = 0; pass <= passes; ++pass) {
            g_allocations = 0;
            for (const std::vector<float>& f : features) {
                const std::int64_t ns = timed([&] {
                    g_counting.store(true, std::memory_order_relaxed);
                    descriptor_penalties(view, f.data(), f.size() / view.feature_dim, scratch.data(), penalties.data());
                    g_counting.store(false, std::memory_order_relaxed);
                });
                g_sink = static_cast<std::uint32_t>(penalties[0] > 1.0f);
                if (pass > 0) per_clip.push_back(ns);
            }
            if (pass > 0) allocations += g_allocations.load();
        }
        char what[160];
        std::snprintf(what, sizeof what,
                      "stage: clip descriptor, pyramid and penalties (per clip, %zu floats, %zu labels)",
                      view.descriptor_size(), static_cast<std::size_t>(view.label_count));
        report.latency.push_back({"hdm05, hdm05-accurate.config", what, summarize(per_clip)});
        char line[256];
        std::snprintf(line, sizeof line,
                      "hdm05-accurate.config's clip descriptor: the %zu validation clips average %.1f characters; heap "
                      "allocations during %d timed passes: %ld",
                      clips.size(), static_cast<double>(characters) / static_cast<double>(clips.size()), passes,
                      allocations);
        report.notes.push_back(line);

        // The whole clip's label (clip.hpp's classify_clip(): the strings to every
        // representative, the votes, the exemplars and the descriptor), what a
        // gesture between two events costs when it ends, from the same characters.
        std::vector<float> clip_scratch(clip_scratch_floats(view));
        std::vector<detail::Cell> cells(clip_cells(view, longest));
        std::vector<std::int64_t> per_label;
        long label_allocations = 0;
        for (int pass = 0; pass <= passes; ++pass) {
            g_allocations = 0;
            for (std::size_t i = 0; i < strings.size(); ++i) {
                const std::int64_t ns = timed([&] {
                    g_counting.store(true, std::memory_order_relaxed);
                    const Classification c = classify_clip(view, strings[i].data(), features[i].data(),
                                                           records[i].empty() ? nullptr : records[i].data(),
                                                           strings[i].size(), clip_scratch.data(), cells.data());
                    g_counting.store(false, std::memory_order_relaxed);
                    g_sink = c.label;
                });
                if (pass > 0) per_label.push_back(ns);
            }
            if (pass > 0) label_allocations += g_allocations.load();
        }
        std::snprintf(what, sizeof what,
                      "whole clip's label, classify_clip() (per clip, %zu representatives of %u characters)",
                      static_cast<std::size_t>(view.representative_count), view.total_representative_chars());
        report.latency.push_back({"hdm05, hdm05-accurate.config", what, summarize(per_label)});
        std::snprintf(line, sizeof line,
                      "hdm05-accurate.config's whole-clip labels (classify_clip()): heap allocations during %d timed "
                      "passes: %ld",
                      passes, label_allocations);
        report.notes.push_back(line);

        // The motion directions (descriptor.hpp), which only whole-clip
        // classification pays too: the same settings with three levels of
        // directions (what msr.config carries; HDM05's folds are at their
        // ceiling either way), each validation clip's histograms and penalties
        // timed once per pass from its characters' records.
        host::TrainingOptions directed_options = accurate;
        directed_options.direction_levels = 3;
        directed_options.direction_ridge = 3000.0;
        directed_options.direction_weight = 2.0;
        const host::ModelData directed = host::train_model(training, directed_options, nullptr);
        const ModelView directed_view = directed.view();
        std::vector<std::vector<float>> directed_records;
        for (const host::Clip& clip : clips)
            directed_records.push_back(host::encode_clip(directed_view, clip, false, true).records);
        std::vector<float> direction_scratch(directed_view.direction_size()), directed_penalties(view.label_count);
        std::vector<std::int64_t> per_directions;
        long direction_allocations = 0;
        for (int pass = 0; pass <= passes; ++pass) {
            g_allocations = 0;
            for (const std::vector<float>& r : directed_records) {
                const std::int64_t ns = timed([&] {
                    g_counting.store(true, std::memory_order_relaxed);
                    direction_penalties(directed_view, r.data(), r.size() / directed_view.direction_record_floats(),
                                        direction_scratch.data(), directed_penalties.data());
                    g_counting.store(false, std::memory_order_relaxed);
                });
                g_sink = static_cast<std::uint32_t>(directed_penalties[0] > 1.0f);
                if (pass > 0) per_directions.push_back(ns);
            }
            if (pass > 0) direction_allocations += g_allocations.load();
        }
        std::snprintf(what, sizeof what,
                      "stage: motion directions, histograms and penalties (per clip, %zu floats, %zu labels)",
                      directed_view.direction_size(), static_cast<std::size_t>(directed_view.label_count));
        report.latency.push_back({"hdm05, hdm05-accurate.config + directions", what, summarize(per_directions)});
        std::snprintf(line, sizeof line,
                      "hdm05-accurate.config with three levels of motion directions: heap allocations during %d "
                      "timed passes of their histograms and penalties: %ld",
                      passes, direction_allocations);
        report.notes.push_back(line);
    }

    std::vector<ScalingPoint> points;
    if (scaling) {
        bench::ModelSize base;
        base.covariance = Covariance::full;
        points.push_back(measure_scaling("base", base));
        for (int J : {20, 80}) {
            auto s = base;
            s.components = J;
            points.push_back(measure_scaling("J", s));
        }
        for (int d : {12, 48}) {
            auto s = base;
            s.feature_dim = d;
            points.push_back(measure_scaling("d", s));
        }
        for (int K : {32, 256}) {
            auto s = base;
            s.characters = K;
            points.push_back(measure_scaling("K", s));
        }
        for (int R : {15, 90, 250}) {
            auto s = base;
            s.representatives = R;
            points.push_back(measure_scaling("representatives", s));
        }
        for (int M : {16, 64}) {  // the segmenter weighing M centres per label (10 labels)
            auto s = base;
            s.exemplars_per_label = M;
            points.push_back(measure_scaling("exemplars per label", s));
        }
        {  // the same 64 centres per label in the feature's first 12 of 24 coordinates (exemplar_dim)
            auto s = base;
            s.exemplars_per_label = 64;
            s.exemplar_dims = 12;
            points.push_back(measure_scaling("exemplars in 12 of d's coordinates", s));
        }
        for (double w : {1.0, 4.0}) {
            auto s = base;
            s.window_seconds = w;
            s.step_seconds = w / 4;
            s.representative_length = static_cast<int>(w * 15);
            points.push_back(measure_scaling("window", s));
        }
    }

    const std::string machine = machine_description();
    std::ostringstream md;
    md << "Machine: " << machine << ". Stream: the " << clips.size() << " clips of hdm05/val.tsv joined, "
       << stream.frame_count() << " frames at 120 Hz; " << passes
       << " timed passes after one warm-up pass. Clock overhead "
       << "(an empty timed call, median): " << overhead << " ns, included in every figure.\n\n"
       << "| model | measured | n | median ns | p99 ns | p99.9 ns | max ns |\n|---|---|---:|---:|---:|---:|---:|\n";
    char cell[512];
    for (const auto& row : report.latency) {
        std::snprintf(cell, sizeof cell, "| %s | %s | %zu | %.0f | %.0f | %.0f | %.0f |\n", row.model.c_str(),
                      row.what.c_str(), row.stats.n, row.stats.median, row.stats.p99, row.stats.p999, row.stats.max);
        md << cell;
    }
    md << "\n";
    for (const auto& note : report.notes) md << "- " << note << "\n";
    std::snprintf(cell, sizeof cell, "- training the J=40 model on hdm05/train.tsv (%zu clips): %.1f s\n",
                  training.size(), train_seconds);
    md << cell;
    md << "\n| state bytes (storage) | annotator, both rules | annotator, segmenter alone | encoder | matcher | segmenter |\n|---|---:|---:|---:|---:|---:|\n"
       << memory_md.str();
    md << "\n| table bytes | normalise | PCA | GMM | tree + W | strings | votes | total (every table) |\n"
          "|---|---:|---:|---:|---:|---:|---:|---:|\n"
       << tables_md.str();
    if (!points.empty()) {
        md << "\nScaling on random models (31 joints, full covariance; base J=40, d=24, K=64, 30 representatives of 30 "
              "characters, 2 s windows every 0.5 s at 12 characters/s), " << kScalingPasses << " passes over a 30 s 120 Hz stream:\n\n"
              "| varied | J | d | K | representatives | window s | exemplars per label | median ns (all frames) | median ns (character frames) | p99.9 ns | segmenter alone: character frames median / p99 ns | work spread: character frames median / p99 ns, every frame p99 / max ns |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const auto& p : points) {
            std::snprintf(
                cell, sizeof cell,
                "| %s | %d | %d | %d | %d | %.1f | %d | %.0f | %.0f | %.0f | %.0f / %.0f | %.0f / %.0f, %.0f / %.0f |\n",
                p.varied.c_str(), p.size.components, p.size.feature_dim, p.size.characters, p.size.representatives,
                p.size.window_seconds, p.size.exemplars_per_label, p.every.median, p.character.median, p.every.p999,
                p.own_character.median, p.own_character.p99, p.spread_character.median, p.spread_character.p99,
                p.spread_every.p99, p.spread_every.max);
            md << cell;
        }
    }
    std::fputs(md.str().c_str(), stdout);
    if (!markdown_path.empty()) std::ofstream(markdown_path) << md.str();
    if (!json_path.empty()) {
        std::ofstream json(json_path);
        json << "{\n  \"machine\": " << host::json_string(machine) << ",\n  \"frames\": " << stream.frame_count()
             << ",\n  \"passes\": " << passes << ",\n  \"clock_overhead_ns\": " << overhead << ",\n  \"latency_ns\": [";
        for (std::size_t i = 0; i < report.latency.size(); ++i) {
            const auto& r = report.latency[i];
            json << (i ? ",\n    " : "\n    ") << "{\"model\": " << host::json_string(r.model)
                 << ", \"measured\": " << host::json_string(r.what) << ", \"n\": " << r.stats.n
                 << ", \"median\": " << r.stats.median << ", \"p99\": " << r.stats.p99
                 << ", \"p99_9\": " << r.stats.p999 << ", \"max\": " << r.stats.max << ", \"mean\": " << r.stats.mean
                 << "}";
        }
        json << "\n  ],\n  \"models\": [" << report.json_models.str()
             << "],\n  \"training_seconds_j40\": " << train_seconds << ",\n  \"scaling\": [";
        for (std::size_t i = 0; i < points.size(); ++i) {
            const auto& p = points[i];
            json << (i ? ",\n    " : "\n    ") << "{\"varied\": \"" << p.varied
                 << "\", \"components\": " << p.size.components << ", \"feature_dim\": " << p.size.feature_dim
                 << ", \"characters\": " << p.size.characters << ", \"representatives\": " << p.size.representatives
                 << ", \"window_seconds\": " << p.size.window_seconds
                 << ", \"exemplars_per_label\": " << p.size.exemplars_per_label
                 << ", \"exemplar_dims\": " << p.size.exemplar_dims << ", \"median_ns\": " << p.every.median
                 << ", \"character_median_ns\": " << p.character.median << ", \"p99_9_ns\": " << p.every.p999
                 << ", \"own_character_median_ns\": " << p.own_character.median
                 << ", \"own_character_p99_ns\": " << p.own_character.p99
                 << ", \"spread_character_median_ns\": " << p.spread_character.median
                 << ", \"spread_character_p99_ns\": " << p.spread_character.p99
                 << ", \"spread_every_p99_ns\": " << p.spread_every.p99
                 << ", \"spread_every_max_ns\": " << p.spread_every.max << "}";
        }
        json << "\n  ]\n}\n";
    }
    return 0;
}
