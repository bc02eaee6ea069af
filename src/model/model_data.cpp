#include "model/model_data.hpp"

#include "actionstring/gmm.hpp"
#include "actionstring/normalize.hpp"
#include "io/clip.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>

namespace actionstring {
namespace host {

void ModelData::add_representative(const std::vector<Character>& chars, LabelId label) {
    if (chars.empty()) throw std::invalid_argument("representative string is empty");
    representative_chars.insert(representative_chars.end(), chars.begin(), chars.end());
    representative_offsets.push_back(static_cast<std::uint32_t>(representative_chars.size()));
    representative_labels.push_back(label);
}

ModelView ModelData::view() const {
    auto data_or_null = [](const auto& v) { return v.empty() ? nullptr : v.data(); };
    ModelView m;
#define ACTIONSTRING_VIEW_OF_SCALAR(T, FIELD, INITIAL, LOW, HIGH) m.FIELD = FIELD;
#define ACTIONSTRING_VIEW_OF_COUNT(T, FIELD, TABLE) m.FIELD = static_cast<T>(TABLE.size());
#define ACTIONSTRING_VIEW_OF_TABLE(T, FIELD, SIZE, LOW, HIGH) m.FIELD = data_or_null(FIELD);
#define ACTIONSTRING_VIEW_OF_NAMES(FIELD, COUNT) m.FIELD = FIELD.table();
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_VIEW_OF_SCALAR, ACTIONSTRING_VIEW_OF_COUNT, ACTIONSTRING_VIEW_OF_TABLE,
                              ACTIONSTRING_VIEW_OF_NAMES)
#undef ACTIONSTRING_VIEW_OF_SCALAR
#undef ACTIONSTRING_VIEW_OF_COUNT
#undef ACTIONSTRING_VIEW_OF_TABLE
#undef ACTIONSTRING_VIEW_OF_NAMES
    return m;
}

std::vector<std::string> name_strings(const NameTable& names, std::size_t count) {
    std::vector<std::string> out;
    if (!names.present()) return out;
    for (std::size_t i = 0; i < count; ++i) out.emplace_back(names[i]);
    return out;
}

const char* mismatched_table(const ModelData& model) {
    // In schema order: each size expression reads only fields listed before it,
    // which are checked by then, so no expression reads past a table.
    const ModelView m = model.view();
#define ACTIONSTRING_CHECK_SCALAR(T, FIELD, INITIAL, LOW, HIGH)
#define ACTIONSTRING_CHECK_COUNT(T, FIELD, TABLE) \
    if (model.TABLE.size() != static_cast<std::size_t>(m.FIELD)) return #TABLE;
#define ACTIONSTRING_CHECK_TABLE(T, FIELD, SIZE, LOW, HIGH) \
    if (model.FIELD.size() != static_cast<std::size_t>(SIZE)) return #FIELD;
#define ACTIONSTRING_CHECK_NAMES(FIELD, COUNT) \
    if (model.FIELD.size() != static_cast<std::size_t>(COUNT)) return #FIELD;
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_CHECK_SCALAR, ACTIONSTRING_CHECK_COUNT, ACTIONSTRING_CHECK_TABLE,
                              ACTIONSTRING_CHECK_NAMES)
#undef ACTIONSTRING_CHECK_SCALAR
#undef ACTIONSTRING_CHECK_COUNT
#undef ACTIONSTRING_CHECK_TABLE
#undef ACTIONSTRING_CHECK_NAMES
    return nullptr;
}

void check_model(const ModelData& model, const std::string& name) {
    if (const char* table = mismatched_table(model))
        throw ReadError(name, 0, std::string("the size of table '") + table + "' does not agree with the fields it depends on");
    if (model.node_characters.size() > 32767) throw ReadError(name, 0, "node_characters: more than 32767 tree nodes");
    const ModelView view = model.view();
    const char* problem = "";
    if (validate_model(view, &problem) != Status::ok) throw ReadError(name, 0, std::string("invalid model: ") + problem);
    if (view.has_gmm() && !gmm_is_overflow_safe(view, max_pose_coordinate))
        throw ReadError(name, 0, "invalid model: gmm_factors: a pose the runtime accepts could overflow the GMM in float");
}

std::size_t table_bytes(const ModelView& m) {
    std::size_t bytes = 0;
#define ACTIONSTRING_BYTES_SCALAR(T, FIELD, INITIAL, LOW, HIGH)
#define ACTIONSTRING_BYTES_COUNT(T, FIELD, TABLE)
#define ACTIONSTRING_BYTES_TABLE(T, FIELD, SIZE, LOW, HIGH) \
    if (m.FIELD != nullptr) bytes += sizeof(T) * static_cast<std::size_t>(SIZE);
#define ACTIONSTRING_BYTES_NAMES(FIELD, COUNT)
    ACTIONSTRING_MODEL_FIELDS(ACTIONSTRING_BYTES_SCALAR, ACTIONSTRING_BYTES_COUNT, ACTIONSTRING_BYTES_TABLE,
                              ACTIONSTRING_BYTES_NAMES)
#undef ACTIONSTRING_BYTES_SCALAR
#undef ACTIONSTRING_BYTES_COUNT
#undef ACTIONSTRING_BYTES_TABLE
#undef ACTIONSTRING_BYTES_NAMES
    return bytes;
}

void interleave_gmm_factors(ModelData& model) {
    const ModelView view = model.view();
    const std::size_t size = view.factor_size();
    if (model.gmm_factors.size() != view.component_count * size)
        throw std::invalid_argument("interleave_gmm_factors: gmm_factors does not hold J factors");
    std::vector<float> interleaved(model.gmm_factors.size());
    for (std::size_t j = 0; j < view.component_count; ++j)
        for (std::size_t k = 0; k < size; ++k)
            interleaved[view.gmm_factor_index(j, k)] = model.gmm_factors[j * size + k];
    model.gmm_factors = std::move(interleaved);
}

void set_gmm(ModelData& model, const std::vector<Eigen::VectorXd>& means,
             const std::vector<Eigen::MatrixXd>& covariances, const std::vector<double>& weights, Covariance kind) {
    const std::size_t J = means.size();
    if (J == 0 || covariances.size() != J || weights.size() != J)
        throw std::invalid_argument("set_gmm: means, covariances and weights differ in count");
    const Eigen::Index d = means[0].size();
    if (d == 0) throw std::invalid_argument("set_gmm: empty mean");
    const double log_2pi = std::log(2.0 * 3.14159265358979323846);
    model.component_count = static_cast<std::uint16_t>(J);
    model.covariance = kind;
    model.gmm_means.clear();
    model.gmm_factors.clear();
    model.gmm_log_normalizers.clear();
    model.gmm_log_weights.clear();
    for (std::size_t j = 0; j < J; ++j) {
        const Eigen::MatrixXd& cov = covariances[j];
        if (means[j].size() != d || cov.rows() != d || cov.cols() != d)
            throw std::invalid_argument("set_gmm: component " + std::to_string(j) + " has the wrong size");
        if (!(weights[j] > 0.0)) throw std::invalid_argument("set_gmm: weights must be positive");
        for (Eigen::Index c = 0; c < d; ++c) model.gmm_means.push_back(static_cast<float>(means[j][c]));
        double log_det_u = 0.0;
        if (kind == Covariance::diagonal) {
            for (Eigen::Index c = 0; c < d; ++c) {
                if (!(cov(c, c) > 0.0)) throw std::invalid_argument("set_gmm: non-positive variance");
                const double u = 1.0 / std::sqrt(cov(c, c));
                model.gmm_factors.push_back(static_cast<float>(u));
                log_det_u += std::log(u);
            }
        } else {
            if (!cov.isApprox(cov.transpose(), 1e-9))
                throw std::invalid_argument("set_gmm: covariance is not symmetric");
            Eigen::LLT<Eigen::MatrixXd> cov_llt(cov);
            if (cov_llt.info() != Eigen::Success)
                throw std::invalid_argument("set_gmm: covariance is not positive definite");
            const Eigen::MatrixXd precision = cov_llt.solve(Eigen::MatrixXd::Identity(d, d));
            Eigen::LLT<Eigen::MatrixXd> prec_llt(0.5 * (precision + precision.transpose()));
            if (prec_llt.info() != Eigen::Success)
                throw std::invalid_argument("set_gmm: precision is not positive definite");
            const Eigen::MatrixXd upper = prec_llt.matrixU();  // precision = Uᵀ U
            for (Eigen::Index c = 0; c < d; ++c)
                for (Eigen::Index r = 0; r <= c; ++r) model.gmm_factors.push_back(static_cast<float>(upper(r, c)));
            for (Eigen::Index c = 0; c < d; ++c) log_det_u += std::log(upper(c, c));
        }
        model.gmm_log_normalizers.push_back(static_cast<float>(-0.5 * static_cast<double>(d) * log_2pi + log_det_u));
        model.gmm_log_weights.push_back(static_cast<float>(std::log(weights[j])));
    }
    model.feature_dim = static_cast<std::uint16_t>(d);
    interleave_gmm_factors(model);  // built component by component above
}

void set_character_distances_from_leaves(ModelData& model) {
    const std::size_t K = model.character_count, J = model.view().tree_dim();
    std::vector<const float*> leaf(K, nullptr);
    for (std::size_t n = 0; n < model.node_characters.size(); ++n)
        if (model.node_children[2 * n] < 0) leaf.at(model.node_characters[n]) = &model.node_centroids[n * J];
    model.character_distances.assign(K * K, 0.0f);
    for (std::size_t a = 0; a < K; ++a)
        for (std::size_t b = 0; b < K; ++b) {
            if (leaf[a] == nullptr || leaf[b] == nullptr)
                throw std::invalid_argument("set_character_distances_from_leaves: a character has no leaf");
            double sum = 0.0;
            for (std::size_t j = 0; j < J; ++j) sum += std::fabs(double(leaf[a][j]) - double(leaf[b][j]));
            model.character_distances[a * K + b] = static_cast<float>(sum);
        }
}

}  // namespace host
}  // namespace actionstring
