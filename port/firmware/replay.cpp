// actionstring firmware replay: runs a recorded stream (a generated header of
// constexpr tables) through the annotator frame by frame and prints what a
// device would act on. The same source builds for the host (port/posix) and
// for a Cortex-M4F (port/cortex_m); lines that do not start with '#' must be
// identical on both, which tests/firmware checks. '#' lines carry measurements
// (per-frame cycles, state bytes, stack) that differ by platform.
//
// No heap, no exceptions, no stdio: output goes through port::log_write().
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>

#include "actionstring/annotator.hpp"
#include "actionstring_port.hpp"
#include ACTIONSTRING_REPLAY_MODEL_HEADER
#include ACTIONSTRING_REPLAY_STREAM_HEADER

namespace model = ACTIONSTRING_REPLAY_MODEL_NAMESPACE;
namespace stream = actionstring_stream;
using actionstring::Annotator;

namespace {

/// One output line assembled in a fixed buffer, then written in one go.
class Line {
public:
    Line& text(const char* s) {
        while (*s != '\0' && length_ + 2 < sizeof buffer_) buffer_[length_++] = *s++;
        return *this;
    }
    Line& number(std::uint64_t value) {
        char digits[24];
        std::size_t n = 0;
        do {
            digits[n++] = static_cast<char>('0' + value % 10u);
            value /= 10u;
        } while (value != 0u);
        while (n > 0 && length_ + 2 < sizeof buffer_) buffer_[length_++] = digits[--n];
        return *this;
    }
    Line& hex(std::uint32_t value) {
        for (int shift = 28; shift >= 0; shift -= 4) {
            const auto nibble = static_cast<unsigned>(value >> static_cast<unsigned>(shift)) & 0xFu;
            if (length_ + 2 < sizeof buffer_) buffer_[length_++] = "0123456789abcdef"[nibble];
        }
        return *this;
    }
    void write() {
        buffer_[length_++] = '\n';
        buffer_[length_] = '\0';
        actionstring::port::log_write(buffer_);
        length_ = 0;
    }

private:
    char buffer_[192] = {};
    std::size_t length_ = 0;
};

std::uint32_t fnv1a(std::uint32_t hash, std::uint32_t value) {
    for (int byte = 0; byte < 4; ++byte) {
        hash ^= (value >> (8 * byte)) & 0xFFu;
        hash *= 16777619u;
    }
    return hash;
}

#if defined(__arm__)
// A loop of known length: 2 instructions per iteration (subs, bne). Measuring it
// converts the clock into instructions where the clock counts instructions
// (QEMU with -icount) and gives cycles per instruction on real silicon.
std::uint32_t calibration_cycles(std::uint32_t iterations) {
    const std::uint64_t begin = actionstring::port::cycle_count();
    __asm__ volatile("1: subs %0, %0, #1\n\tbne 1b" : "+r"(iterations) : : "cc");
    return static_cast<std::uint32_t>(actionstring::port::cycle_count() - begin);
}
#endif

// The state lives in zero-initialised storage (.bss), not in an initialised
// object the start-up code would have to copy from flash. Its size is the
// model's own (the generated kAnnotatorBytes): the model's settings, so the
// segmenter alone labels the stream; it is the better rule on streams of
// actions, and leaving the paper's window matcher out halves the state.
// The second pass spreads the work, which queues two poses: its bytes, when more.
constexpr actionstring::AnnotatorConfig spread_settings() {
    actionstring::AnnotatorConfig config = actionstring::annotator_config(model::kModel);
    config.spread_work = true;
    return config;
}
constexpr std::size_t kSpreadBytes = Annotator::required_bytes(model::kModel, spread_settings());
alignas(Annotator) unsigned char annotator_object[sizeof(Annotator)];
actionstring::StateBuffer<(kSpreadBytes > model::kAnnotatorBytes ? kSpreadBytes : model::kAnnotatorBytes)>
    annotator_state;

const char* name(actionstring::LabelId label) {
    return label == actionstring::unknown_label ? "unknown" : model::kModel.label_names[label];
}

// Feeds frame f of the stream and writes its cost: "<tag>f cycles characters settled".
actionstring::FrameResult timed_frame(Annotator& annotator, Line& line, const char* tag, std::uint32_t f) {
    const float* positions = stream::kFramePositions + static_cast<std::size_t>(f) * stream::kJointCount * 3u;
    const std::uint64_t begin = actionstring::port::cycle_count();
    const actionstring::FrameResult result = annotator.push_frame(stream::kFrameTimeUs[f], positions);
    const std::uint64_t cycles = actionstring::port::cycle_count() - begin;
    line.text(tag)
        .number(f)
        .text(" ")
        .number(cycles)
        .text(" ")
        .number(result.characters)
        .text(" ")
        .number(result.characters_settled)
        .write();
    return result;
}

}  // namespace

int main() {
    static_assert(stream::kJointCount == model::kModel.joint_count, "the stream's skeleton is the model's");
    Annotator& annotator = *new (annotator_object) Annotator();
    Line line;
    const actionstring::Status status = annotator.init(model::kModel, actionstring::annotator_config(model::kModel),
                                                       annotator_state.data(), annotator_state.size());
    if (status != actionstring::Status::ok) {
        line.text("model rejected: ").text(actionstring::status_name(status)).write();
        return 1;
    }
    line.text("replay: ")
        .number(stream::kFrameCount)
        .text(" frames, ")
        .number(stream::kSegmentCount)
        .text(" clips, model ")
        .text(model::kModelChecksum)
        .write();
    line.text("# port ").text(actionstring::port::name()).write();
    line.text("# state bytes: annotator object ")
        .number(sizeof(Annotator))
        .text(" storage ")
        .number(annotator_state.size())
        .text(" encoder ")
        .number(actionstring::StringEncoder::required_bytes(model::kModel))
        .text(" segmenter ")
        .number(
            actionstring::ActionSegmenter::required_bytes(model::kModel, actionstring::segmenter_config(model::kModel)))
        .write();
#if defined(__arm__)
    line.text("# calibration instructions 2000000 cycles ").number(calibration_cycles(1000000u)).write();
#endif

    std::uint32_t hash = 2166136261u;
    std::uint32_t settled_hash = 2166136261u;  // the settled labels alone, in character order
    std::uint32_t settled = 0, rejected = 0;
    std::uint32_t segment = 0;
    actionstring::LabelId shown = actionstring::unknown_label;
    for (std::uint32_t f = 0; f < stream::kFrameCount; ++f) {
        if (segment < stream::kSegmentCount && stream::kSegmentFirstFrame[segment] == f)
            line.text("truth ").number(f).text(" ").text(stream::kSegmentLabel[segment++]).write();
        const actionstring::FrameResult result = timed_frame(annotator, line, "# cycles ", f);
        if (result.status != actionstring::Status::ok && result.status != actionstring::Status::stream_restarted) {
            ++rejected;
            line.text("rejected ").number(f).text(" ").text(actionstring::status_name(result.status)).write();
        }
        // A device acts on settled labels: print each change with the character it starts at.
        for (std::uint32_t k = 0; k < result.characters_settled; ++k) {
            const std::uint64_t character = annotator.settled_character() - (result.characters_settled - 1u - k);
            const actionstring::LabelId label = annotator.settled_label(character);
            ++settled;
            hash = fnv1a(hash, static_cast<std::uint32_t>(label));
            settled_hash = fnv1a(settled_hash, static_cast<std::uint32_t>(label));
            if (label == shown) continue;
            shown = label;
            line.text("settled ").number(f).text(" char ").number(character).text(" ").text(name(label)).write();
        }
        hash = fnv1a(hash, static_cast<std::uint32_t>(annotator.live_label()));
    }
    line.text("end: frames ")
        .number(stream::kFrameCount)
        .text(" settled ")
        .number(settled)
        .text(" rejected ")
        .number(rejected)
        .text(" characters ")
        .number(annotator.characters())
        .text(" labels fnv1a32 ")
        .hex(hash)
        .write();
    // Again with each character's work (encoder and segmenter) spread over the frames until
    // the next (AnnotatorConfig::spread_work), in the same storage: the same
    // settled labels, a flatter cost per frame ('# spread cycles' lines).
    const actionstring::AnnotatorConfig spread_config = spread_settings();
    if (annotator.init(model::kModel, spread_config, annotator_state.data(), annotator_state.size()) !=
        actionstring::Status::ok) {
        line.text("spread: model rejected").write();
        return 1;
    }
    std::uint32_t spread_hash = 2166136261u, spread_settled = 0;
    const auto take = [&](const actionstring::FrameResult& result) {
        for (std::uint32_t k = 0; k < result.characters_settled; ++k) {
            const std::uint64_t character = annotator.settled_character() - (result.characters_settled - 1u - k);
            spread_hash = fnv1a(spread_hash, static_cast<std::uint32_t>(annotator.settled_label(character)));
            ++spread_settled;
        }
    };
    for (std::uint32_t f = 0; f < stream::kFrameCount; ++f) {
        take(timed_frame(annotator, line, "# spread cycles ", f));
    }
    take(annotator.finish_work());
    const bool same = spread_settled == settled && spread_hash == settled_hash;
    line.text("spread: settled ")
        .number(spread_settled)
        .text(" labels fnv1a32 ")
        .hex(spread_hash)
        .text(same ? " (the same settled labels)" : " (OTHER settled labels)")
        .write();
    if (!same) return 1;
#if defined(__arm__)
    line.text("# stack bytes used ")
        .number(actionstring_board_stack_used())
        .text(" of ")
        .number(actionstring_board_stack_size())
        .write();
#endif
    annotator.~Annotator();
    return 0;
}
