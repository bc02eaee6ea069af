// actionstring — a binary model read in place (design.md §3).
//
// A model blob is the model as one flat, little-endian, aligned block of
// bytes: a header, one directory entry per schema field (model_schema.hpp)
// in schema order, then the tables, each at a multiple of 16 bytes. The
// runtime checks it once — magic, version, byte order, size, checksum, every
// entry's kind and element size, every table's place and length, integer
// ranges, then validate_model() — and then reads it where it lies: no copy,
// no allocation, no parsing per frame. The ModelView it fills points into the
// blob, which must outlive it (and stay unchanged).
//
// Layout (all integers little-endian):
//   0  char[8]  magic "ASTRBLOB"
//   8  u32      format version (blob_version)
//   12 u32      byte-order mark 0x01020304 (reads differently on a big-endian CPU)
//   16 u64      total bytes
//   24 u64      FNV-1a 64 of the whole blob with these 8 bytes taken as zero
//   32 u32      directory entries (the schema's field count)
//   36 u32      header bytes (64)
//   40 u8[24]   zero
//   64 entries of 32 bytes: u32 kind, u32 element bytes, u64 a, u64 b, u64 c
//        scalar or count: a = the value's bytes (zero-extended)
//        table:           a = offset, b = element count
//        names:           a = offset of the text, b = its bytes, c = offset of the count + 1 offsets (u32)
//   then the tables.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "actionstring/gmm.hpp"
#include "actionstring/model.hpp"
#include "actionstring/normalize.hpp"
#include "actionstring/status.hpp"

namespace actionstring {

/// Version of the blob layout this runtime reads.
// 3: the label bounds; 4: interleaved GMM factors; 5: exemplars; 6: acceleration;
// 7: the events' shortest action; 8: the exemplars' dimension; 9: the clip descriptor;
// 10: the labels' lead; 11: the clip's motion directions; 12: early settling
constexpr std::uint32_t blob_version = 13;
/// Alignment a blob's first byte must have (its tables are aligned to it within).
constexpr std::size_t blob_alignment = 16;

namespace detail {

constexpr char blob_magic[8] = {'A', 'S', 'T', 'R', 'B', 'L', 'O', 'B'};
constexpr std::uint32_t blob_byte_order = 0x01020304u;
constexpr std::size_t blob_header_bytes = 64;
constexpr std::size_t blob_entry_bytes = 32;
constexpr std::size_t blob_checksum_at = 24;

/// Directory entry kinds.
enum class BlobKind : std::uint32_t { scalar = 1, count = 2, table = 3, names = 4 };

/// Fields in the schema (the directory's length).
constexpr std::uint32_t blob_field_count() noexcept {
    std::uint32_t n = 0;
#define ACTIONSTRING_BLOB_COUNT_SCALAR(T, FIELD, INITIAL, LOW, HIGH) ++n;
#define ACTIONSTRING_BLOB_COUNT_COUNT(T, FIELD, TABLE) ++n;
#define ACTIONSTRING_BLOB_COUNT_TABLE(T, FIELD, SIZE, LOW, HIGH) ++n;
#define ACTIONSTRING_BLOB_COUNT_NAMES(FIELD, COUNT) ++n;
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_BLOB_COUNT_SCALAR, ACTIONSTRING_BLOB_COUNT_COUNT,
                              ACTIONSTRING_BLOB_COUNT_TABLE, ACTIONSTRING_BLOB_COUNT_NAMES)
#undef ACTIONSTRING_BLOB_COUNT_SCALAR
#undef ACTIONSTRING_BLOB_COUNT_COUNT
#undef ACTIONSTRING_BLOB_COUNT_TABLE
#undef ACTIONSTRING_BLOB_COUNT_NAMES
    return n;
}

/// Little-endian reads that do not depend on the CPU's byte order or alignment.
inline std::uint32_t blob_u32(const unsigned char* p) noexcept {
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}
inline std::uint64_t blob_u64(const unsigned char* p) noexcept {
    return static_cast<std::uint64_t>(blob_u32(p)) | static_cast<std::uint64_t>(blob_u32(p + 4)) << 32;
}

/// FNV-1a 64 of a blob, its checksum field taken as zero.
inline std::uint64_t blob_checksum(const unsigned char* bytes, std::size_t size) noexcept {
    std::uint64_t hash = 14695981039346656037ull;
    for (std::size_t i = 0; i < size; ++i) {
        const bool in_field = i >= blob_checksum_at && i < blob_checksum_at + 8;
        hash ^= in_field ? 0u : bytes[i];
        hash *= 1099511628211ull;
    }
    return hash;
}

/// Reads one directory entry after another, checking each against the schema.
class BlobReader {
public:
    BlobReader(const unsigned char* bytes, std::size_t size) noexcept : bytes_(bytes), size_(size) {}

    /// A scalar's value: kind, element size, unused bytes zero, integers within [low, high].
    template <class T>
    bool scalar(BlobKind kind, T& out, long long low, long long high) noexcept {
        const unsigned char* e = next(kind, sizeof(T));
        if (e == nullptr) return false;
        const std::uint64_t raw = blob_u64(e + 8);
        if (sizeof(T) < 8 && (raw >> (8 * sizeof(T))) != 0) return false;
        if (blob_u64(e + 16) != 0 || blob_u64(e + 24) != 0) return false;
        unsigned char value[sizeof(T)];
        for (std::size_t i = 0; i < sizeof(T); ++i) value[i] = static_cast<unsigned char>(raw >> (8 * i));
        std::memcpy(&out, value, sizeof(T));
        return in_range(out, low, high);
    }

    /// A table: in bounds, aligned, integers within [low, high]; its element
    /// count goes to `count` (model_from_blob() checks it against the schema).
    template <class T>
    bool table(const T*& out, std::uint64_t& count, long long low, long long high) noexcept {
        const unsigned char* e = next(BlobKind::table, sizeof(T));
        if (e == nullptr) return false;
        const std::uint64_t offset = blob_u64(e + 8);
        count = blob_u64(e + 16);
        if (blob_u64(e + 24) != 0) return false;
        if (count == 0) {
            out = nullptr;
            return offset == 0;
        }
        const unsigned char* p = span(offset, count, sizeof(T));
        if (p == nullptr) return false;
        out = reinterpret_cast<const T*>(p);
        for (std::size_t i = 0; i < count; ++i)
            if (!in_range(out[i], low, high)) return false;
        return true;
    }

    /// `count` packed names: text and offsets in bounds and consistent (names_ok() checks the rest).
    bool names(NameTable& out, std::size_t count) noexcept {
        const unsigned char* e = next(BlobKind::names, 1);
        if (e == nullptr) return false;
        const std::uint64_t text_at = blob_u64(e + 8), text_bytes = blob_u64(e + 16), offsets_at = blob_u64(e + 24);
        if (count == 0) {
            out = NameTable{};
            return text_at == 0 && text_bytes == 0 && offsets_at == 0;
        }
        const unsigned char* text = span(text_at, text_bytes, 1);
        const unsigned char* offsets = span(offsets_at, count + 1, sizeof(std::uint32_t));
        if (text == nullptr || offsets == nullptr) return false;
        out = NameTable{reinterpret_cast<const char*>(text), reinterpret_cast<const std::uint32_t*>(offsets)};
        // The last offset is the text's length, so no name reaches past it.
        return out.offsets[count] == text_bytes && names_ok(out, count);
    }

private:
    template <class T>
    static bool in_range(T value, long long low, long long high) noexcept {
        if constexpr (std::is_floating_point_v<T>) {
            (void)low, (void)high;
            return true;  // floats: validate_model() bounds what matters
        } else {
            const auto v = static_cast<long long>(value);
            return v >= low && v <= high;
        }
    }

    // The next directory entry, if it has this kind and element size.
    const unsigned char* next(BlobKind kind, std::size_t element_bytes) noexcept {
        const unsigned char* e = bytes_ + blob_header_bytes + blob_entry_bytes * index_++;
        if (blob_u32(e) != static_cast<std::uint32_t>(kind) || blob_u32(e + 4) != element_bytes) return nullptr;
        return e;
    }

    // count × size bytes at offset, inside the blob after the directory, aligned.
    const unsigned char* span(std::uint64_t offset, std::uint64_t count, std::size_t size) const noexcept {
        const std::uint64_t tables = blob_header_bytes + std::uint64_t{blob_entry_bytes} * blob_field_count();
        if (offset < tables || offset > size_ || offset % blob_alignment != 0) return nullptr;
        if (count > (size_ - offset) / size) return nullptr;
        return bytes_ + offset;
    }

    const unsigned char* bytes_;
    std::size_t size_;
    std::size_t index_ = 0;
};

}  // namespace detail

/// Reads a model blob in place.
///
/// @param bytes   the blob, aligned to blob_alignment; it must outlive `model`
///                and every state object initialised from it, unchanged
/// @param size    its length in bytes
/// @param model   receives the view (pointing into `bytes`) when ok; untouched otherwise
/// @param problem if not null, receives what is wrong (static storage)
/// @return ok; invalid_argument (null or misaligned bytes); or invalid_model
///         (not a blob, another version or byte order, truncated, checksum
///         mismatch, an entry or table that disagrees with the schema, or a
///         model validate_model() refuses)
inline Status model_from_blob(const void* bytes, std::size_t size, ModelView& model,
                              const char** problem = nullptr) noexcept {
    using detail::refuse;
    if (bytes == nullptr || reinterpret_cast<std::uintptr_t>(bytes) % blob_alignment != 0) {
        if (problem != nullptr) *problem = "blob: null or not aligned to 16 bytes";
        return Status::invalid_argument;
    }
    const auto* b = static_cast<const unsigned char*>(bytes);
    const std::uint32_t fields = detail::blob_field_count();
    const std::size_t directory_end = detail::blob_header_bytes + detail::blob_entry_bytes * fields;
    if (size < detail::blob_header_bytes || std::memcmp(b, detail::blob_magic, 8) != 0)
        return refuse(problem, "blob: not an actionstring model blob");
    if (detail::blob_u32(b + 8) != blob_version)
        return refuse(problem, "blob: another format version (export it again with this build)");
    std::uint32_t order;
    std::memcpy(&order, b + 12, sizeof order);
    if (detail::blob_u32(b + 12) != detail::blob_byte_order) return refuse(problem, "blob: byte-order mark damaged");
    if (order != detail::blob_byte_order) return refuse(problem, "blob: this CPU is not little-endian");
    if (detail::blob_u64(b + 16) != size) return refuse(problem, "blob: truncated, or its size field is wrong");
    if (detail::blob_u32(b + 32) != fields || detail::blob_u32(b + 36) != detail::blob_header_bytes ||
        size < directory_end)
        return refuse(problem, "blob: its directory does not match this runtime's model schema");
    if (detail::blob_checksum(b, size) != detail::blob_u64(b + detail::blob_checksum_at))
        return refuse(problem, "blob: checksum mismatch (damaged)");

    // Pass 1, in schema order: every entry, each table bounded by the blob.
    detail::BlobReader reader(b, size);
    ModelView m;
#define ACTIONSTRING_BLOB_SCALAR(T, FIELD, INITIAL, LOW, HIGH) \
    if (!reader.scalar(detail::BlobKind::scalar, m.FIELD, LOW, HIGH)) return refuse(problem, #FIELD ": bad blob entry");
#define ACTIONSTRING_BLOB_COUNT(T, FIELD, TABLE) \
    if (!reader.scalar(detail::BlobKind::count, m.FIELD, 0, 65535)) return refuse(problem, #FIELD ": bad blob entry");
#define ACTIONSTRING_BLOB_TABLE(T, FIELD, SIZE, LOW, HIGH) \
    std::uint64_t FIELD##_count = 0;                       \
    if (!reader.table(m.FIELD, FIELD##_count, LOW, HIGH))  \
        return refuse(problem, #FIELD ": table out of bounds, misaligned or out of range");
#define ACTIONSTRING_BLOB_NAMES(FIELD, COUNT)                    \
    if (!reader.names(m.FIELD, static_cast<std::size_t>(COUNT))) \
        return refuse(problem, #FIELD ": names out of bounds or not NUL-terminated");
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_BLOB_SCALAR, ACTIONSTRING_BLOB_COUNT, ACTIONSTRING_BLOB_TABLE,
                              ACTIONSTRING_BLOB_NAMES)
#undef ACTIONSTRING_BLOB_SCALAR
#undef ACTIONSTRING_BLOB_COUNT
#undef ACTIONSTRING_BLOB_TABLE
#undef ACTIONSTRING_BLOB_NAMES
    // Pass 2, in schema order: each table's length is the one the schema
    // derives from the fields before it (checked by then, so no size
    // expression reads past a table).
#define ACTIONSTRING_BLOB_SCALAR(T, FIELD, INITIAL, LOW, HIGH)
#define ACTIONSTRING_BLOB_COUNT(T, FIELD, TABLE)
#define ACTIONSTRING_BLOB_TABLE(T, FIELD, SIZE, LOW, HIGH) \
    if (FIELD##_count != static_cast<std::uint64_t>(SIZE)) \
        return refuse(problem, #FIELD ": table length disagrees with the fields it depends on");
#define ACTIONSTRING_BLOB_NAMES(FIELD, COUNT)
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_BLOB_SCALAR, ACTIONSTRING_BLOB_COUNT, ACTIONSTRING_BLOB_TABLE,
                              ACTIONSTRING_BLOB_NAMES)
#undef ACTIONSTRING_BLOB_SCALAR
#undef ACTIONSTRING_BLOB_COUNT
#undef ACTIONSTRING_BLOB_TABLE
#undef ACTIONSTRING_BLOB_NAMES
    if (validate_model(m, problem) != Status::ok) return Status::invalid_model;
    if (m.has_gmm() && !gmm_is_overflow_safe(m, max_pose_coordinate))
        return refuse(problem, "gmm_factors: a pose the runtime accepts could overflow the GMM in float");
    model = m;
    return Status::ok;
}

}  // namespace actionstring
