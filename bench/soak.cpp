// Soak: a day of 120 Hz frames through the committed model's annotator, as a
// device would run it, twice: with a 64-bit clock, and with a 32-bit
// microsecond timer that wraps every 71.6 minutes. Checks that labels keep
// changing to the end, that memory and per-frame time stay flat, and that a
// wrapping clock costs one restart per wrap and no frames.
//
// The stream is the clips of hdm05/val.tsv joined and repeated with the clock
// running on; without the data, the benchmark says so and exits 77.
//   actionstring_soak [--hours H] [--json FILE] [--markdown FILE]
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "common/json.hpp"
#include "common/stats.hpp"
#include "hdm05_model.hpp"
#include "io/clip_list.hpp"
#include "io/stream.hpp"
#include "io/text.hpp"
#include "run/skeleton.hpp"

namespace host = actionstring::host;
namespace model = actionstring_hdm05;
using Clock = std::chrono::steady_clock;

namespace {

// Resident set size in bytes (Linux), or 0.
std::uint64_t resident_bytes() {
    std::FILE* f = std::fopen("/proc/self/statm", "r");
    if (f == nullptr) return 0;
    unsigned long pages_total = 0, pages_resident = 0;
    const int n = std::fscanf(f, "%lu %lu", &pages_total, &pages_resident);
    std::fclose(f);
    return n == 2 ? static_cast<std::uint64_t>(pages_resident) * 4096u : 0u;
}

struct HourFigures {
    std::uint64_t frames = 0, accepted = 0, rejected = 0, restarts = 0, settled_changes = 0;
    std::vector<double> frame_ns;  // a sample: every 64th frame
    std::uint64_t rss = 0;
};

struct SoakResult {
    std::string clock;
    std::vector<HourFigures> hours;
    double seconds = 0;
};

SoakResult soak(const host::ConcatenatedStream& stream, double hours, bool wrap32) {
    // Both rules, in static-size storage as a device keeps it.
    actionstring::AnnotatorConfig config = actionstring::annotator_config(model::kModel);
    config.window_rule = true;
    auto storage = std::make_unique<actionstring::StateBuffer<model::kAnnotatorWithWindowsBytes>>();
    auto annotator = std::make_unique<actionstring::Annotator>();
    if (annotator->init(model::kModel, config, storage->data(), storage->size()) != actionstring::Status::ok) {
        std::fprintf(stderr, "actionstring_soak: the committed model was refused\n");
        std::exit(1);
    }
    SoakResult result;
    result.clock = wrap32 ? "32-bit microsecond timer (wraps every 71.6 min)" : "64-bit microseconds";
    const std::int64_t period_us = stream.times_us[1] - stream.times_us[0];
    const std::int64_t loop_us = stream.times_us.back() - stream.times_us.front() + period_us;
    const auto total_frames = static_cast<std::uint64_t>(hours * 3600.0 * 120.0);
    const std::uint64_t frames_per_hour = 3600u * 120u;
    // Every measurement buffer is allocated and touched before the first frame,
    // so resident memory measures the annotator, not the bookkeeping.
    const std::size_t hour_count = static_cast<std::size_t>((total_frames + frames_per_hour - 1) / frames_per_hour);
    result.hours.resize(hour_count);
    for (HourFigures& h : result.hours) h.frame_ns.assign(frames_per_hour / 64 + 1, 0.0);
    std::vector<std::size_t> samples(hour_count, 0);
    actionstring::LabelId last_settled = actionstring::unknown_label;
    const auto start = Clock::now();
    for (std::uint64_t f = 0; f < total_frames; ++f) {
        const std::size_t hour_index = static_cast<std::size_t>(f / frames_per_hour);
        HourFigures& hour = result.hours[hour_index];
        const std::size_t i = f % stream.frame_count();
        const std::int64_t loops = static_cast<std::int64_t>(f / stream.frame_count());
        const std::int64_t true_us = loops * loop_us + (stream.times_us[i] - stream.times_us.front());
        const std::int64_t stamp = wrap32 ? static_cast<std::int64_t>(static_cast<std::uint32_t>(true_us)) : true_us;
        const bool timed = f % 64 == 0;
        const auto before = timed ? Clock::now() : Clock::time_point{};
        const actionstring::FrameResult r = annotator->push_frame(stamp, stream.frame(i));
        if (timed)
            hour.frame_ns[samples[hour_index]++] = std::chrono::duration<double, std::nano>(Clock::now() - before).count();
        ++hour.frames;
        const bool accepted = r.status == actionstring::Status::ok || r.status == actionstring::Status::stream_restarted;
        hour.accepted += accepted;
        hour.rejected += !accepted;
        hour.restarts += r.status == actionstring::Status::stream_restarted;
        // Every character the frame settled (several with early settling), in order.
        const std::uint64_t last = annotator->settled_character();
        for (std::uint64_t c = last + 1 - r.characters_settled; r.characters_settled > 0 && c <= last; ++c)
            if (annotator->settled_label(c) != last_settled) {
                last_settled = annotator->settled_label(c);
                ++hour.settled_changes;
            }
        if (f % frames_per_hour == frames_per_hour - 1 || f + 1 == total_frames) {
            hour.frame_ns.resize(samples[hour_index]);
            std::sort(hour.frame_ns.begin(), hour.frame_ns.end());
            hour.rss = resident_bytes();
        }
    }
    result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
    return result;
}

void report(const SoakResult& r, host::JsonWriter& json, std::string& md) {
    std::uint64_t frames = 0, rejected = 0, restarts = 0;
    for (const HourFigures& h : r.hours) frames += h.frames, rejected += h.rejected, restarts += h.restarts;
    const HourFigures& first = r.hours.front();
    const HourFigures& last = r.hours.back();
    json.begin_object()
        .field("clock", r.clock)
        .field("hours", static_cast<long long>(r.hours.size()))
        .field("frames", static_cast<unsigned long>(frames))
        .field("rejected_frames", static_cast<unsigned long>(rejected))
        .field("restarts", static_cast<unsigned long>(restarts))
        .field("wall_seconds", r.seconds);
    json.key("per_hour").begin_array();
    for (const HourFigures& h : r.hours)
        json.begin_object()
            .field("settled_label_changes", static_cast<unsigned long>(h.settled_changes))
            .field("restarts", static_cast<unsigned long>(h.restarts))
            .field("rejected", static_cast<unsigned long>(h.rejected))
            .field("frame_ns_median", host::sorted_quantile(h.frame_ns, 0.5))
            .field("frame_ns_p99", host::sorted_quantile(h.frame_ns, 0.99))
            .field("rss_bytes", static_cast<unsigned long>(h.rss))
            .end_object();
    json.end_array().end_object();
    char line[512];
    std::snprintf(line, sizeof line,
                  "| %s | %zu h | %llu | %llu | %llu | %llu → %llu | %.0f → %.0f ns | %.1f → %.1f µs | %.1f → %.1f MiB | "
                  "%.0f s |\n",
                  r.clock.c_str(), r.hours.size(), static_cast<unsigned long long>(frames),
                  static_cast<unsigned long long>(rejected), static_cast<unsigned long long>(restarts),
                  static_cast<unsigned long long>(first.settled_changes),
                  static_cast<unsigned long long>(last.settled_changes), host::sorted_quantile(first.frame_ns, 0.5),
                  host::sorted_quantile(last.frame_ns, 0.5), host::sorted_quantile(first.frame_ns, 0.99) / 1000.0,
                  host::sorted_quantile(last.frame_ns, 0.99) / 1000.0, static_cast<double>(first.rss) / 1048576.0,
                  static_cast<double>(last.rss) / 1048576.0, r.seconds);
    md += line;
}

}  // namespace

int main(int argc, char** argv) {
    double hours = 24.0;
    std::string json_path, md_path;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--hours" && i + 1 < argc) hours = std::atof(argv[++i]);
        else if (arg == "--json" && i + 1 < argc) json_path = argv[++i];
        else if (arg == "--markdown" && i + 1 < argc) md_path = argv[++i];
        else {
            std::fprintf(stderr, "usage: actionstring_soak [--hours H] [--json FILE] [--markdown FILE]\n");
            return 2;
        }
    }
    if (!(hours > 0 && hours <= 24 * 7)) {
        std::fprintf(stderr, "actionstring_soak: --hours must be in (0, 168]\n");
        return 2;
    }
    const char* env = std::getenv("ACTIONSTRING_DATA");
    const std::string data = env != nullptr ? env : std::string(ACTIONSTRING_SOURCE_DIR) + "/../shared/data";
    std::vector<host::LabelledClip> clips;
    try {
        clips = host::load_labelled_clips(data + "/hdm05/val.tsv");
        host::conform_to_model(model::kModel, clips);
    } catch (const std::exception& error) {
        std::fprintf(stderr, "actionstring_soak: %s\nThe soak replays HDM05 recordings: set ACTIONSTRING_DATA.\n",
                     error.what());
        return 77;
    }
    std::vector<host::StreamSegment> segments;
    for (const host::LabelledClip& c : clips) segments.push_back({&c.clip, c.label, 0.0});
    const host::ConcatenatedStream stream = host::concatenate_stream(segments);

    host::JsonWriter json;
    json.begin_object().field("model", model::kModelChecksum).field("stream_frames", stream.frame_count());
    json.key("runs").begin_array();
    std::string md =
        "| clock | length | frames | rejected | restarts | settled label changes, first → last hour | median frame, "
        "first → last hour | p99 frame | resident memory | wall |\n|---|---|---:|---:|---:|---|---|---|---|---:|\n";
    for (const bool wrap32 : {false, true}) {
        const SoakResult r = soak(stream, hours, wrap32);
        report(r, json, md);
        std::fprintf(stderr, "actionstring_soak: %s done in %.0f s\n", r.clock.c_str(), r.seconds);
    }
    json.end_array().end_object();
    std::fputs(md.c_str(), stdout);
    if (!json_path.empty()) host::write_file(json_path, json.str());
    if (!md_path.empty()) host::write_file(md_path, md);
    return 0;
}
