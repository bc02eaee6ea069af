// A consumer of actionstring::runtime: a hand-written constexpr model (the
// shape a generated header takes) and a short stream. Exit code 0 when the
// runtime labels a raised hand as "hold_up".
#include <actionstring/actionstring.hpp>

#include <cstdio>
#include <cstring>

#if defined(ACTIONSTRING_CONSUMER_EXPECT_WIDE)
static_assert(ACTIONSTRING_DETAIL_WIDE_LANES == 8, "ACTIONSTRING_AVX2 reaches the files that link actionstring::runtime");
#endif

namespace {

using namespace actionstring;

// Joints: 0 pelvis, 1 left hip, 2 right hip, 3 hand. The pose is the hand alone.
constexpr std::uint16_t kPoseJoints[] = {3};
constexpr float kMeans[] = {0.0f, -0.2f, 0.3f, 0.0f, 0.6f, 0.3f};         // hand down, hand up
constexpr float kFactors[] = {10.0f, 10.0f, 10.0f, 10.0f, 10.0f, 10.0f};  // σ = 0.1 m
constexpr float kLogNormalizers[] = {4.1510f, 4.1510f};                   // −1.5·log 2π + 3·log 10
constexpr float kLogWeights[] = {-0.6931f, -0.6931f};
constexpr float kCentroids[] = {0.5f, 0.5f, 1.0f, 0.0f, 0.0f, 1.0f};
constexpr std::int16_t kChildren[] = {1, 2, -1, -1, -1, -1};
constexpr Character kNodeCharacters[] = {0, 0, 1};
constexpr float kW[] = {0.0f, 2.0f, 2.0f, 0.0f};
constexpr std::uint32_t kOffsets[] = {0, 8, 16};
constexpr Character kStrings[] = {0, 0, 1, 1, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1};
constexpr LabelId kLabels[] = {0, 1};
constexpr char kLabelText[] = "wave\0hold_up";
constexpr std::uint32_t kLabelOffsets[] = {0, 5, 13};

constexpr ModelView make_model() {
    ModelView m{};
    m.joint_count = 4;
    m.root_joint = 0;
    m.left_hip_joint = 1;
    m.right_hip_joint = 2;
    m.up_axis = 1;
    m.pose_joint_count = 1;
    m.pose_joints = kPoseJoints;
    m.feature_dim = 3;
    m.component_count = 2;
    m.covariance = Covariance::diagonal;
    m.gmm_means = kMeans;
    m.gmm_factors = kFactors;
    m.gmm_log_normalizers = kLogNormalizers;
    m.gmm_log_weights = kLogWeights;
    m.node_count = 3;
    m.node_centroids = kCentroids;
    m.node_children = kChildren;
    m.node_characters = kNodeCharacters;
    m.character_count = 2;
    m.character_distances = kW;
    m.string_period_us = 100000;
    m.representative_count = 2;
    m.representative_offsets = kOffsets;
    m.representative_chars = kStrings;
    m.representative_labels = kLabels;
    m.label_count = 2;
    m.label_names = NameTable{kLabelText, kLabelOffsets};
    m.window_chars = 8;
    m.step_chars = 4;
    return m;
}

constexpr ModelView kModel = make_model();
constexpr AnnotatorConfig kConfig = [] {
    AnnotatorConfig config = annotator_config(kModel);
    config.window_rule = true;
    return config;
}();
Annotator annotator;
StateBuffer<Annotator::required_bytes(kModel, kConfig)> state;

}  // namespace

int main() {
    if (annotator.init(kModel, kConfig, state.data(), state.size()) != Status::ok) return 2;
    // Standing at x = 1 facing any way, right hand raised.
    for (int frame = 0; frame < 60; ++frame) {
        const float positions[] = {1.0f, 1.0f, 0.0f, 1.0f, 1.0f, -0.1f, 1.0f, 1.0f, 0.1f, 1.0f, 1.6f, 0.3f};
        annotator.push_frame(frame * 33333, positions);
    }
    std::printf("consumer: label %s, confidence %.2f\n", annotator.label_name(),
                static_cast<double>(annotator.confidence()));
    return std::strcmp(annotator.label_name(), "hold_up") == 0 ? 0 : 1;
}
