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
    fuzz::stream_and_check(view);
    delete[] storage;
    return 0;
}
