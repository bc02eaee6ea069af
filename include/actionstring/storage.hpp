// actionstring — caller-owned storage for the state objects.
//
// No state object holds arrays of its own. Each one states how many bytes a
// model needs (`required_bytes(model, …)`, constexpr when the model is) and
// works in storage the caller passes to `init(…, storage, bytes)`: a static
// array on a device (StateBuffer, sized by the `constexpr` a generated header
// emits), exactly what a loaded model needs on a host. So no compile-time
// limit caps the model, and nothing is allocated at run time.
//
// Lifetime: the storage belongs to the caller, must be aligned to
// state_alignment, and must stay alive and unmoved while the state object is
// used (until its next init()). init() clears it; the state keeps no other copy.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace actionstring {

/// Alignment the storage of every state object must have. Every array inside
/// it starts at a multiple of this too, so SIMD loads of a row never split.
constexpr std::size_t state_alignment = 16;

/// What required_bytes() returns when a model's sizes overflow the address
/// space (only a hostile model does): no storage is that large.
constexpr std::size_t unsatisfiable_bytes = SIZE_MAX;

/// Fixed storage of `Bytes` bytes, aligned for a state object: the static
/// array of a firmware image.
///
///     static actionstring::StateBuffer<model::kAnnotatorBytes> state;
///     annotator.init(model::kModel, config, state.data(), state.size());
template <std::size_t Bytes>
struct StateBuffer {
    static_assert(Bytes > 0 && Bytes != unsatisfiable_bytes, "a StateBuffer needs a positive, possible size");
    alignas(state_alignment) unsigned char bytes[Bytes];

    void* data() noexcept { return bytes; }
    static constexpr std::size_t size() noexcept { return Bytes; }
};

namespace detail {

/// Places arrays one after another in one block, each aligned to
/// state_alignment. Sizes saturate at unsatisfiable_bytes, so no count from a
/// hostile model can wrap around to a small size. Used by each state object's
/// plan(), which both required_bytes() and init() read: the sizes are written once.
class StorageLayout {
public:
    /// Reserves `count` elements of T and returns their offset in the block.
    template <class T>
    constexpr std::size_t add(std::size_t count) noexcept {
        return add_bytes(count, sizeof(T));
    }
    constexpr std::size_t add_bytes(std::size_t count, std::size_t size) noexcept {
        const std::size_t offset = bytes_;
        if (bytes_ == unsatisfiable_bytes) return offset;
        if (size != 0 && count > (unsatisfiable_bytes - state_alignment) / size) {
            bytes_ = unsatisfiable_bytes;
            return offset;
        }
        const std::size_t length = (count * size + state_alignment - 1) / state_alignment * state_alignment;
        bytes_ = length > unsatisfiable_bytes - 1 - bytes_ ? unsatisfiable_bytes : bytes_ + length;
        return offset;
    }
    /// Total bytes so far (a multiple of state_alignment), or unsatisfiable_bytes.
    constexpr std::size_t bytes() const noexcept { return bytes_; }

private:
    std::size_t bytes_ = 0;
};

/// Whether `storage` can hold a block of `needed` bytes: large enough and,
/// unless nothing is needed, non-null and aligned.
inline bool storage_fits(const void* storage, std::size_t bytes, std::size_t needed) noexcept {
    if (needed == unsatisfiable_bytes || bytes < needed) return false;
    return needed == 0 || (storage != nullptr && reinterpret_cast<std::uintptr_t>(storage) % state_alignment == 0);
}

/// The array at `offset` of a block (the block was cleared by init()).
template <class T>
T* storage_at(void* storage, std::size_t offset) noexcept {
    return reinterpret_cast<T*>(static_cast<unsigned char*>(storage) + offset);
}

/// Clears a block: every float 0, every index 0, so no state reads a byte it did not write.
inline void clear_storage(void* storage, std::size_t bytes) noexcept {
    if (storage != nullptr && bytes > 0) std::memset(storage, 0, bytes);
}

}  // namespace detail
}  // namespace actionstring
