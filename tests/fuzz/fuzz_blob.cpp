// libFuzzer entry point for the model blob, read in place by the runtime
// (model_from_blob). Inputs of even length get a valid checksum, so the
// fuzzer reaches the directory, the tables and validation rather than stopping
// at the checksum; odd ones keep theirs. Any input must end in a refusal, or
// in a model the runtime's init() accepts and streams with labels in range
// and nothing read outside the blob: anything else (crash, sanitizer report,
// hang, an out-of-range label, NaN) is a bug.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/blob.hpp"
#include "fuzz_frames.hpp"
#include "run/state.hpp"

using namespace actionstring;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    // An exact-size aligned copy, so ASan sees any read past the blob's end.
    struct Block {
        alignas(blob_alignment) unsigned char bytes[blob_alignment];
    };
    const std::size_t blocks = (size + blob_alignment - 1) / blob_alignment;
    auto* storage = new Block[blocks == 0 ? 1 : blocks];
    unsigned char* bytes = storage[0].bytes;
    if (size > 0) std::memcpy(bytes, data, size);
    if (size % 2 == 0 && size >= 32) {
        const std::uint64_t sum = detail::blob_checksum(bytes, size);
        for (std::size_t i = 0; i < 8; ++i)
            bytes[detail::blob_checksum_at + i] = static_cast<unsigned char>(sum >> (8 * i));
    }
    ModelView view;
    const char* problem = nullptr;
    const Status status = model_from_blob(bytes, size, view, &problem);
    if (status != Status::ok) {
        if (problem == nullptr) std::abort();  // every refusal says why
        delete[] storage;
        return 0;
    }
    AnnotatorConfig config = annotator_config(view);
    config.window_rule = true;
    // A valid model may still ask for more state than a fuzzing run should allocate.
    if (Annotator::required_bytes(view, config) <= (std::size_t{64} << 20)) {
        host::Stateful<Annotator> annotator;
        const Status init = annotator.init(view, config);
        if (init != Status::ok && init != Status::model_exceeds_capacity) std::abort();
        if (init == Status::ok) {
            for (int step = 0; step < 40; ++step) {
                const std::vector<float> frame = fuzz::frame_for(view, step);
                annotator->push_frame(static_cast<std::int64_t>(step) * 40000, frame.data());
                const LabelId label = annotator->label(), live = annotator->live_label();
                if (label != unknown_label && label >= view.label_count) std::abort();
                if (live != unknown_label && live >= view.label_count) std::abort();
                if (!std::isfinite(annotator->confidence())) std::abort();
                if (live != unknown_label && std::strlen(view.label_names[live]) == 0) std::abort();
            }
        }
    }
    delete[] storage;
    return 0;
}
