// The model blob: written from the schema, read back through the runtime.
#include "model/blob.hpp"

#include <algorithm>
#include <cstring>
#include <memory>
#include <type_traits>
#include <vector>

#include "actionstring/blob.hpp"
#include "io/text.hpp"

namespace actionstring {
namespace host {
namespace {

// Bytes of a value in little-endian order, whatever the host's order.
template <class T>
void put_le(std::string& out, std::size_t at, T value) {
    static_assert(std::is_trivially_copyable_v<T>, "plain values only");
    using Bits =
        std::conditional_t<sizeof(T) == 1, std::uint8_t,
                           std::conditional_t<sizeof(T) == 2, std::uint16_t,
                                              std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>>>;
    Bits bits;
    std::memcpy(&bits, &value, sizeof bits);
    for (std::size_t i = 0; i < sizeof(T); ++i) out[at + i] = static_cast<char>((bits >> (8 * i)) & 0xFFu);
}

class BlobWriter {
public:
    BlobWriter() : out_(detail::blob_header_bytes + detail::blob_entry_bytes * detail::blob_field_count(), '\0') {}

    template <class T>
    void scalar(detail::BlobKind kind, T value) {
        std::uint64_t bits = 0;
        std::string raw(8, '\0');
        put_le(raw, 0, value);
        for (std::size_t i = 0; i < sizeof(T); ++i)
            bits |= std::uint64_t{static_cast<unsigned char>(raw[i])} << (8 * i);
        entry(kind, sizeof(T), bits, 0, 0);
    }
    template <class T>
    void table(const std::vector<T>& values) {
        const std::uint64_t at = values.empty() ? 0 : append(values.size() * sizeof(T));
        for (std::size_t i = 0; i < values.size(); ++i) put_le(out_, at + i * sizeof(T), values[i]);
        entry(detail::BlobKind::table, sizeof(T), at, values.size(), 0);
    }
    void names(const NameList& names) {
        if (names.empty()) {
            entry(detail::BlobKind::names, 1, 0, 0, 0);
            return;
        }
        const std::string& text = names.packed_text();
        const std::uint64_t text_at = append(text.size());
        std::memcpy(&out_[text_at], text.data(), text.size());
        const std::vector<std::uint32_t>& offsets = names.packed_offsets();
        const std::uint64_t offsets_at = append(offsets.size() * sizeof(std::uint32_t));
        for (std::size_t i = 0; i < offsets.size(); ++i) put_le(out_, offsets_at + 4 * i, offsets[i]);
        entry(detail::BlobKind::names, 1, text_at, text.size(), offsets_at);
    }

    std::string finish() {
        append(0);  // the length a multiple of the alignment too, so blobs can be stored end to end
        std::memcpy(&out_[0], detail::blob_magic, 8);
        put_le(out_, 8, blob_version);
        put_le(out_, 12, detail::blob_byte_order);
        put_le(out_, 16, static_cast<std::uint64_t>(out_.size()));
        put_le(out_, 32, detail::blob_field_count());
        put_le(out_, 36, static_cast<std::uint32_t>(detail::blob_header_bytes));
        const auto* bytes = reinterpret_cast<const unsigned char*>(out_.data());
        put_le(out_, detail::blob_checksum_at, detail::blob_checksum(bytes, out_.size()));
        return std::move(out_);
    }

private:
    void entry(detail::BlobKind kind, std::uint32_t element_bytes, std::uint64_t a, std::uint64_t b, std::uint64_t c) {
        const std::size_t at = detail::blob_header_bytes + detail::blob_entry_bytes * index_++;
        put_le(out_, at, static_cast<std::uint32_t>(kind));
        put_le(out_, at + 4, element_bytes);
        put_le(out_, at + 8, a);
        put_le(out_, at + 16, b);
        put_le(out_, at + 24, c);
    }
    // Room for `bytes` at the next multiple of the blob's alignment.
    std::uint64_t append(std::size_t bytes) {
        const std::size_t at = (out_.size() + blob_alignment - 1) / blob_alignment * blob_alignment;
        out_.resize(at + bytes, '\0');
        return at;
    }

    std::string out_;
    std::size_t index_ = 0;
};

// An owning copy of every table a view points to (the view was validated, so
// each table holds the length its size expression gives).
ModelData copy_view(const ModelView& m) {
    ModelData data;
    data.representative_offsets.clear();
#define ACTIONSTRING_COPY_SCALAR(T, FIELD, INITIAL, LOW, HIGH) data.FIELD = m.FIELD;
#define ACTIONSTRING_COPY_COUNT(T, FIELD, TABLE)
#define ACTIONSTRING_COPY_TABLE(T, FIELD, SIZE, LOW, HIGH) \
    if (m.FIELD != nullptr) data.FIELD.assign(m.FIELD, m.FIELD + static_cast<std::size_t>(SIZE));
#define ACTIONSTRING_COPY_NAMES(FIELD, COUNT)                                \
    {                                                                        \
        const std::vector<std::string> names = name_strings(m.FIELD, COUNT); \
        data.FIELD.assign(names.begin(), names.end());                       \
    }
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_COPY_SCALAR, ACTIONSTRING_COPY_COUNT, ACTIONSTRING_COPY_TABLE,
                              ACTIONSTRING_COPY_NAMES)
#undef ACTIONSTRING_COPY_SCALAR
#undef ACTIONSTRING_COPY_COUNT
#undef ACTIONSTRING_COPY_TABLE
#undef ACTIONSTRING_COPY_NAMES
    return data;
}

}  // namespace

bool looks_like_blob(std::string_view bytes) {
    return bytes.size() >= 8 && std::memcmp(bytes.data(), detail::blob_magic, 8) == 0;
}

std::string write_blob(const ModelData& model) {
    check_model(model, "the model");
    const ModelView v = model.view();
    BlobWriter w;
#define ACTIONSTRING_PUT_SCALAR(T, FIELD, INITIAL, LOW, HIGH) w.scalar(detail::BlobKind::scalar, model.FIELD);
#define ACTIONSTRING_PUT_COUNT(T, FIELD, TABLE) w.scalar(detail::BlobKind::count, v.FIELD);
#define ACTIONSTRING_PUT_TABLE(T, FIELD, SIZE, LOW, HIGH) w.table(model.FIELD);
#define ACTIONSTRING_PUT_NAMES(FIELD, COUNT) w.names(model.FIELD);
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_PUT_SCALAR, ACTIONSTRING_PUT_COUNT, ACTIONSTRING_PUT_TABLE,
                              ACTIONSTRING_PUT_NAMES)
#undef ACTIONSTRING_PUT_SCALAR
#undef ACTIONSTRING_PUT_COUNT
#undef ACTIONSTRING_PUT_TABLE
#undef ACTIONSTRING_PUT_NAMES
    return w.finish();
}

ModelData read_blob(const std::string& name, std::string_view bytes) {
    // The runtime reads a blob in place, aligned: give it an aligned copy.
    struct Block {
        alignas(blob_alignment) unsigned char bytes[blob_alignment];
    };
    std::vector<Block> blocks(bytes.size() / blob_alignment + 1);
    unsigned char* aligned = blocks.front().bytes;
    std::copy(bytes.begin(), bytes.end(), aligned);
    ModelView view;
    const char* problem = "";
    if (model_from_blob(aligned, bytes.size(), view, &problem) != Status::ok)
        throw ReadError(name, 0, std::string("invalid model blob: ") + problem);
    ModelData model = copy_view(view);
    check_model(model, name);
    return model;
}

}  // namespace host
}  // namespace actionstring
