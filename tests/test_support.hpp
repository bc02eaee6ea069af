// Helpers shared by the tests.
#pragma once

#include <cstring>
#include <string>
#include <vector>

#include "actionstring/annotator.hpp"
#include "actionstring/model.hpp"
#include "actionstring/string_distance.hpp"

namespace test {

/// The model's own settings with the paper's window rule on, for tests that read label().
inline actionstring::AnnotatorConfig every_rule(const actionstring::ModelView& model) {
    actionstring::AnnotatorConfig config = actionstring::annotator_config(model);
    config.window_rule = true;
    return config;
}

/// "12345" → {1, 2, 3, 4, 5}.
inline std::vector<actionstring::Character> chars(const std::string& digits) {
    std::vector<actionstring::Character> out;
    for (char c : digits) out.push_back(static_cast<actionstring::Character>(c - '0'));
    return out;
}

/// W = 0 on the diagonal, 1 elsewhere, over K characters.
inline std::vector<float> unit_weights(std::size_t K) {
    std::vector<float> w(K * K, 1.0f);
    for (std::size_t a = 0; a < K; ++a) w[a * K + a] = 0.0f;
    return w;
}

/// Batch distance with a workspace of the right size; CHECKs nothing itself.
inline float batch_distance(const std::vector<actionstring::Character>& query,
                            const std::vector<actionstring::Character>& reference, const std::vector<float>& w,
                            std::size_t K, actionstring::MatchVariant variant,
                            actionstring::LengthNormalization normalization = actionstring::LengthNormalization::none,
                            actionstring::Status* status = nullptr) {
    std::vector<actionstring::detail::Cell> workspace(
        actionstring::string_distance_cells(query.size(), reference.size()));
    float d = -1.0f;
    const auto s = actionstring::string_distance(query.data(), query.size(), reference.data(), reference.size(),
                                                 actionstring::CharacterWeights{w.data(), K}, {variant, normalization},
                                                 workspace.data(), &d);
    if (status != nullptr) *status = s;
    return d;
}

/// Bitwise float equality (distinguishes −0 and compares NaN payloads).
inline bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace test
