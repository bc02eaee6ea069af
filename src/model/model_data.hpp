// actionstring host library — an owning model whose view() drives the runtime.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "actionstring/model.hpp"

namespace actionstring {
namespace host {

/// Names (of joints, of labels), kept beside the packed form a ModelView
/// reads (NameTable: NUL-terminated names end to end, and their offsets).
class NameList {
public:
    template <class Iterator>
    void assign(Iterator first, Iterator last) {
        clear();
        for (; first != last; ++first) push_back(*first);
    }
    void push_back(std::string name) {
        if (offsets_.empty()) offsets_.push_back(0);
        text_.append(name).push_back('\0');
        offsets_.push_back(static_cast<std::uint32_t>(text_.size()));
        names_.push_back(std::move(name));
    }
    void clear() {
        names_.clear();
        text_.clear();
        offsets_.clear();
    }
    std::size_t size() const noexcept { return names_.size(); }
    bool empty() const noexcept { return names_.empty(); }
    const std::string& operator[](std::size_t i) const { return names_[i]; }
    bool operator==(const NameList& other) const { return names_ == other.names_; }
    bool operator!=(const NameList& other) const { return names_ != other.names_; }
    std::vector<std::string>::const_iterator begin() const noexcept { return names_.begin(); }
    std::vector<std::string>::const_iterator end() const noexcept { return names_.end(); }
    const std::vector<std::string>& strings() const noexcept { return names_; }
    /// The packed names (valid until the list changes), or an empty table when there are none.
    NameTable table() const noexcept { return names_.empty() ? NameTable{} : NameTable{text_.data(), offsets_.data()}; }
    /// The packed text (every name and its NUL) and the size() + 1 offsets.
    const std::string& packed_text() const noexcept { return text_; }
    const std::vector<std::uint32_t>& packed_offsets() const noexcept { return offsets_; }

private:
    std::vector<std::string> names_;
    std::string text_;
    std::vector<std::uint32_t> offsets_;
};

/// The names of a table as strings.
std::vector<std::string> name_strings(const NameTable& names, std::size_t count);

/// Every table of a model in host memory: the fields of
/// ACTIONSTRING_MODEL_FIELDS, scalars by value and each table as a vector
/// (the schema's counts are the vectors' sizes). view() returns a ModelView
/// pointing into this object: valid while the object lives and its tables are
/// not resized. Not copyable (a copy would be easy to take for the original
/// while views point into it); movable.
struct ModelData {
    ModelData() { representative_offsets.push_back(0); }
    ModelData(const ModelData&) = delete;
    ModelData& operator=(const ModelData&) = delete;
    ModelData(ModelData&&) = default;
    ModelData& operator=(ModelData&&) = default;

#define ACTIONSTRING_DATA_SCALAR(T, FIELD, INITIAL, LOW, HIGH) T FIELD = INITIAL;
#define ACTIONSTRING_DATA_COUNT(T, FIELD, TABLE)
#define ACTIONSTRING_DATA_TABLE(T, FIELD, SIZE, LOW, HIGH) std::vector<T> FIELD;
#define ACTIONSTRING_DATA_NAMES(FIELD, COUNT) NameList FIELD;
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_DATA_SCALAR, ACTIONSTRING_DATA_COUNT, ACTIONSTRING_DATA_TABLE,
                              ACTIONSTRING_DATA_NAMES)
#undef ACTIONSTRING_DATA_SCALAR
#undef ACTIONSTRING_DATA_COUNT
#undef ACTIONSTRING_DATA_TABLE
#undef ACTIONSTRING_DATA_NAMES

    /// Appends one representative string with its label.
    void add_representative(const std::vector<Character>& chars, LabelId label);

    /// Non-owning view of every table.
    ModelView view() const;
};

/// Where the tables' sizes disagree with the counts and sizes the schema
/// derives from the other fields: the first such table's name, or null when
/// every size agrees. A view of a model that passes may be validated.
const char* mismatched_table(const ModelData& model);

/// Refuses, with a ReadError naming `name` and the field, any model the
/// runtime's init() would refuse for its tables: sizes that disagree,
/// indices out of range, values out of bounds, a GMM that an accepted pose
/// could overflow. The artifact reader and the header generator both call it.
void check_model(const ModelData& model, const std::string& name);

/// Bytes of the model's tables as a generated header stores them (label names excluded).
std::size_t table_bytes(const ModelView& model);

/// Reorders gmm_factors, given component by component (J × factor_size(),
/// each component's elements in order), into the runtime's blocks of four
/// interleaved components (ModelView::gmm_factor_index). For set_gmm() and
/// for reading artifacts written before the interleaved layout.
void interleave_gmm_factors(ModelData& model);

/// Fills the GMM tables from means, covariances and weights given in double.
/// Factors come from the Cholesky factor of each precision; log-normalisers
/// and log-weights are precomputed, so the runtime never inverts anything.
/// Diagonal covariance reads only each covariance's diagonal.
/// Throws std::invalid_argument on size mismatch, a non-positive weight, or a
/// covariance that is not symmetric positive definite.
void set_gmm(ModelData& model, const std::vector<Eigen::VectorXd>& means,
             const std::vector<Eigen::MatrixXd>& covariances, const std::vector<double>& weights, Covariance kind);

/// W[a][b] = L1 distance between the leaf centroids of characters a and b.
void set_character_distances_from_leaves(ModelData& model);

}  // namespace host
}  // namespace actionstring
