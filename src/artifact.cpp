// Model artifact IO and the constexpr header generator.
#include "actionstring_host/artifact.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "actionstring/model.hpp"
#include "actionstring_host/clip.hpp"
#include "actionstring_host/text.hpp"

namespace actionstring {
namespace host {
namespace {

const char kMagic[] = "actionstring-model";

std::string hex_float(float v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "%a", static_cast<double>(v));
    return buffer;
}

template <class T>
void put_ints(std::ostringstream& out, const char* name, const std::vector<T>& values) {
    out << name << ' ' << values.size();
    for (const T v : values) out << ' ' << static_cast<long long>(v);
    out << '\n';
}

void put_floats(std::ostringstream& out, const char* name, const std::vector<float>& values) {
    out << name << ' ' << values.size();
    for (const float v : values) out << ' ' << hex_float(v);
    out << '\n';
}

// Reads the fields in the order serialize_model() writes them.
class FieldReader {
public:
    FieldReader(LineScanner& scanner) : scanner_(scanner) {}

    std::vector<std::string_view> line(const char* name) {
        std::string_view text;
        if (!scanner_.next(text)) scanner_.fail(std::string("file ends where '") + name + "' was expected (truncated?)");
        words_ = split_words(text);
        if (words_.empty() || words_[0] != name)
            scanner_.fail(std::string("expected '") + name + "', got " + quoted(words_.empty() ? std::string_view() : words_[0]));
        return words_;
    }
    long integer(const char* name, long low, long high) {
        const auto words = line(name);
        if (words.size() != 2) scanner_.fail(std::string("expected one value for '") + name + "'");
        return checked(words[1], name, low, high);
    }
    float real(const char* name) {
        const auto words = line(name);
        if (words.size() != 2) scanner_.fail(std::string("expected one value for '") + name + "'");
        return to_float(words[1], name);
    }
    template <class T>
    std::vector<T> ints(const char* name, long low, long high) {
        const auto words = count_line(name);
        std::vector<T> out;
        for (std::size_t i = 2; i < words.size(); ++i) out.push_back(static_cast<T>(checked(words[i], name, low, high)));
        return out;
    }
    std::vector<float> floats(const char* name) {
        const auto words = count_line(name);
        std::vector<float> out;
        for (std::size_t i = 2; i < words.size(); ++i) out.push_back(to_float(words[i], name));
        return out;
    }
    std::string rest_of_line() {
        std::string_view text;
        if (!scanner_.next(text)) scanner_.fail("file ends inside the label names (truncated?)");
        return std::string(text);
    }
    LineScanner& scanner() { return scanner_; }

private:
    std::vector<std::string_view> count_line(const char* name) {
        const auto words = line(name);
        if (words.size() < 2) scanner_.fail(std::string("expected a count for '") + name + "'");
        const long count = checked(words[1], name, 0, 100000000);
        if (static_cast<std::size_t>(count) != words.size() - 2)
            scanner_.fail(std::string("'") + name + "' declares " + std::to_string(count) + " values but has " +
                          std::to_string(words.size() - 2));
        return words;
    }
    long checked(std::string_view token, const char* name, long low, long high) {
        char* end = nullptr;
        const std::string text(token);
        const long long v = std::strtoll(text.c_str(), &end, 10);
        if (end == text.c_str() || *end != '\0' || v < low || v > high)
            scanner_.fail(std::string("expected an integer in [") + std::to_string(low) + ", " + std::to_string(high) + "] for '" + name +
                          "', got " + quoted(token));
        return static_cast<long>(v);
    }
    float to_float(std::string_view token, const char* name) {
        const std::string text(token);
        char* end = nullptr;
        const float v = std::strtof(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || std::isnan(v))
            scanner_.fail(std::string("expected a number for '") + name + "', got " + quoted(token));
        return v;
    }
    LineScanner& scanner_;
    std::vector<std::string_view> words_;
};

std::string body_of(const ModelData& m_const) {
    ModelData& m = const_cast<ModelData&>(m_const);
    std::ostringstream out;
    out << "joint_count " << m.joint_count << '\n'
        << "root_joint " << m.root_joint << '\n'
        << "left_hip_joint " << m.left_hip_joint << '\n'
        << "right_hip_joint " << m.right_hip_joint << '\n'
        << "up_axis " << static_cast<int>(m.up_axis) << '\n'
        << "scale_mode " << static_cast<int>(m.scale_mode) << '\n'
        << "reference_scale " << hex_float(m.reference_scale) << '\n';
    put_ints(out, "pose_joints", m.pose_joints);
    out << "feature_dim " << m.feature_dim << '\n';
    put_floats(out, "projection_mean", m.projection_mean);
    put_floats(out, "projection_matrix", m.projection_matrix);
    out << "component_count " << m.component_count << '\n' << "covariance " << static_cast<int>(m.covariance) << '\n';
    put_floats(out, "gmm_means", m.gmm_means);
    put_floats(out, "gmm_factors", m.gmm_factors);
    put_floats(out, "gmm_log_normalizers", m.gmm_log_normalizers);
    put_floats(out, "gmm_log_weights", m.gmm_log_weights);
    put_floats(out, "node_centroids", m.node_centroids);
    put_ints(out, "node_children", m.node_children);
    put_ints(out, "node_characters", m.node_characters);
    out << "character_count " << m.character_count << '\n';
    put_floats(out, "character_distances", m.character_distances);
    out << "string_period_us " << m.string_period_us << '\n';
    put_ints(out, "representative_offsets", m.representative_offsets);
    put_ints(out, "representative_chars", m.representative_chars);
    put_ints(out, "representative_labels", m.representative_labels);
    out << "label_names " << m.label_names.size() << '\n';
    for (const auto& name : m.label_names) out << name << '\n';
    out << "variant " << static_cast<int>(m.variant) << '\n'
        << "normalization " << static_cast<int>(m.normalization) << '\n'
        << "window_chars " << m.window_chars << '\n'
        << "step_chars " << m.step_chars << '\n'
        << "neighbours " << m.neighbours << '\n'
        << "unknown_distance " << hex_float(m.unknown_distance) << '\n'
        << "end\n";
    return out.str();
}

std::string hex64(std::uint64_t v) {
    char buffer[24];
    std::snprintf(buffer, sizeof buffer, "%016" PRIx64, v);
    return buffer;
}

}  // namespace

std::uint64_t fnv1a64(std::string_view bytes) {
    std::uint64_t hash = 14695981039346656037ull;
    for (const char c : bytes) {
        hash ^= static_cast<unsigned char>(c);
        hash *= 1099511628211ull;
    }
    return hash;
}

std::string serialize_model(ModelData& model) {
    for (const auto& name : model.label_names)
        if (name.empty() || name.find_first_of("\r\n") != std::string::npos)
            throw std::invalid_argument("label names must be non-empty single lines");
    const std::string body = body_of(model);
    return std::string(kMagic) + " " + std::to_string(artifact_version) + "\nchecksum fnv1a64 " + hex64(fnv1a64(body)) + "\n" + body;
}

std::string artifact_checksum(std::string_view text) {
    LineScanner scanner("artifact", text);
    std::string_view line;
    scanner.next(line);
    if (!scanner.next(line)) return {};
    const auto words = split_words(line);
    return words.size() == 3 ? std::string(words[2]) : std::string();
}

ModelData parse_model(const std::string& name, std::string_view text) {
    LineScanner scanner(name, text);
    std::string_view line;
    if (!scanner.next(line)) scanner.fail_at(0, "empty file: expected an actionstring model");
    const auto magic = split_words(line);
    if (magic.size() != 2 || magic[0] != kMagic) scanner.fail("not an actionstring model (expected 'actionstring-model <version>')");
    if (magic[1] != std::to_string(artifact_version))
        scanner.fail("model format version " + std::string(magic[1]) + " is not supported; this build reads version " +
                     std::to_string(artifact_version) + " (retrain or use a matching build)");
    if (!scanner.next(line)) scanner.fail("file ends where the checksum was expected (truncated?)");
    const auto checksum = split_words(line);
    if (checksum.size() != 3 || checksum[0] != "checksum" || checksum[1] != "fnv1a64")
        scanner.fail("expected 'checksum fnv1a64 <hex>'");
    const std::size_t body_start = static_cast<std::size_t>(line.data() + line.size() - text.data()) + 1;
    const std::string_view body = body_start <= text.size() ? text.substr(body_start) : std::string_view();
    if (hex64(fnv1a64(body)) != checksum[2])
        scanner.fail("checksum mismatch: the file is corrupt or was edited (expected " + std::string(checksum[2]) + ", got " +
                     hex64(fnv1a64(body)) + ")");

    FieldReader f(scanner);
    ModelData m;
    m.joint_count = static_cast<std::uint16_t>(f.integer("joint_count", 1, 65535));
    m.root_joint = static_cast<std::uint16_t>(f.integer("root_joint", 0, 65535));
    m.left_hip_joint = static_cast<std::uint16_t>(f.integer("left_hip_joint", 0, 65535));
    m.right_hip_joint = static_cast<std::uint16_t>(f.integer("right_hip_joint", 0, 65535));
    m.up_axis = static_cast<std::uint8_t>(f.integer("up_axis", 0, 2));
    m.scale_mode = static_cast<ScaleMode>(f.integer("scale_mode", 0, 1));
    m.reference_scale = f.real("reference_scale");
    m.pose_joints = f.ints<std::uint16_t>("pose_joints", 0, 65535);
    m.feature_dim = static_cast<std::uint16_t>(f.integer("feature_dim", 0, 65535));
    m.projection_mean = f.floats("projection_mean");
    m.projection_matrix = f.floats("projection_matrix");
    m.component_count = static_cast<std::uint16_t>(f.integer("component_count", 0, 65535));
    m.covariance = static_cast<Covariance>(f.integer("covariance", 0, 1));
    m.gmm_means = f.floats("gmm_means");
    m.gmm_factors = f.floats("gmm_factors");
    m.gmm_log_normalizers = f.floats("gmm_log_normalizers");
    m.gmm_log_weights = f.floats("gmm_log_weights");
    m.node_centroids = f.floats("node_centroids");
    m.node_children = f.ints<std::int16_t>("node_children", -1, 32767);
    m.node_characters = f.ints<Character>("node_characters", 0, 65535);
    m.character_count = static_cast<std::uint16_t>(f.integer("character_count", 0, 65535));
    m.character_distances = f.floats("character_distances");
    m.string_period_us = static_cast<std::uint32_t>(f.integer("string_period_us", 1, 4294967295L));
    m.representative_offsets = f.ints<std::uint32_t>("representative_offsets", 0, 4294967295L);
    m.representative_chars = f.ints<Character>("representative_chars", 0, 65535);
    m.representative_labels = f.ints<LabelId>("representative_labels", 0, 65535);
    const long labels = f.integer("label_names", 1, 65535);
    for (long l = 0; l < labels; ++l) m.label_names.push_back(f.rest_of_line());
    m.variant = static_cast<MatchVariant>(f.integer("variant", 0, 2));
    m.normalization = static_cast<LengthNormalization>(f.integer("normalization", 0, 2));
    m.window_chars = static_cast<std::uint16_t>(f.integer("window_chars", 1, 65535));
    m.step_chars = static_cast<std::uint16_t>(f.integer("step_chars", 1, 65535));
    m.neighbours = static_cast<std::uint16_t>(f.integer("neighbours", 1, 65535));
    m.unknown_distance = f.real("unknown_distance");
    f.line("end");

    // Sizes the view cannot check by itself, then the runtime's own validation.
    const std::size_t J = m.component_count, d = m.feature_dim, D = 3 * m.pose_joints.size();
    const std::size_t factor = m.covariance == Covariance::full ? d * (d + 1) / 2 : d;
    const std::size_t nodes = m.node_characters.size();
    const bool sizes_ok =
        (m.projection_mean.empty() ? m.projection_matrix.empty() : m.projection_mean.size() == D && m.projection_matrix.size() == D * d) &&
        m.gmm_means.size() == J * d && m.gmm_factors.size() == J * factor && m.gmm_log_normalizers.size() == J &&
        m.gmm_log_weights.size() == J && m.node_centroids.size() == nodes * m.view().tree_dim() && m.node_children.size() == 2 * nodes &&
        m.character_distances.size() == static_cast<std::size_t>(m.character_count) * m.character_count &&
        !m.representative_offsets.empty() && m.representative_offsets.size() == m.representative_labels.size() + 1 &&
        m.representative_offsets.back() == m.representative_chars.size() && nodes <= 32767;
    if (!sizes_ok) throw ReadError(name, 0, "table sizes do not agree with each other");
    if (validate_model(m.view()) != Status::ok) throw ReadError(name, 0, "the tables are inconsistent (index out of range or non-finite value)");
    return m;
}

void save_model(ModelData& model, const std::string& path) {
    const std::string text = serialize_model(model);
    std::ofstream out(path, std::ios::binary);
    if (!out) throw ReadError(path, 0, "cannot open for writing");
    out << text;
    if (!out) throw ReadError(path, 0, "cannot write");
}

ModelData load_model(const std::string& path) { return parse_model(path, read_file(path)); }

namespace {

std::string c_string(const std::string& text) {
    std::string out = "\"";
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += ch;
        } else if (c < 0x20 || c >= 0x7F) {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\%03o", c);
            out += buffer;
        } else {
            out += ch;
        }
    }
    return out + "\"";
}

std::string float_literal(float v) {
    if (std::isinf(v)) return v > 0 ? "::actionstring::detail::infinity()" : "-::actionstring::detail::infinity()";
    return hex_float(v) + "f";
}

template <class T, class Format>
void put_array(std::ostringstream& out, const char* type, const char* name, const std::vector<T>& values, Format format,
               const char* prefix = "") {
    if (values.empty()) return;
    out << prefix << "inline constexpr " << type << ' ' << name << "[" << values.size() << "] = {";
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i % 8 == 0) out << "\n    ";
        out << format(values[i]) << (i + 1 < values.size() ? ", " : "");
    }
    out << "\n};\n";
}

}  // namespace

std::string generate_header(ModelData& m, const std::string& checksum, const std::string& ns, const std::string& source_name) {
    const ModelView v = m.view();
    if (validate_model(v) != Status::ok) throw std::invalid_argument("cannot generate a header for an invalid model");
    auto integer = [](auto x) { return std::to_string(static_cast<long long>(x)); };
    std::ostringstream out;
    out << "// DO NOT EDIT. Generated by `actionstring codegen` from " << source_name << "\n"
        << "// (model checksum fnv1a64:" << checksum << "). Regenerate it from the model artifact instead.\n"
        << "#pragma once\n\n#include <cstdint>\n\n#include \"actionstring/capacity.hpp\"\n#include \"actionstring/model.hpp\"\n\n"
        << "namespace " << ns << " {\n\n"
        << "inline constexpr char kModelChecksum[] = \"fnv1a64:" << checksum << "\";\n\n";
    put_array(out, "std::uint16_t", "kPoseJoints", m.pose_joints, integer);
    put_array(out, "float", "kProjectionMean", m.projection_mean, float_literal);
    put_array(out, "float", "kProjectionMatrix", m.projection_matrix, float_literal);
    put_array(out, "float", "kGmmMeans", m.gmm_means, float_literal);
    put_array(out, "float", "kGmmFactors", m.gmm_factors, float_literal);
    put_array(out, "float", "kGmmLogNormalizers", m.gmm_log_normalizers, float_literal);
    put_array(out, "float", "kGmmLogWeights", m.gmm_log_weights, float_literal);
    put_array(out, "float", "kNodeCentroids", m.node_centroids, float_literal);
    put_array(out, "std::int16_t", "kNodeChildren", m.node_children, integer);
    put_array(out, "::actionstring::Character", "kNodeCharacters", m.node_characters, integer);
    put_array(out, "float", "kCharacterDistances", m.character_distances, float_literal);
    put_array(out, "std::uint32_t", "kRepresentativeOffsets", m.representative_offsets, integer);
    put_array(out, "::actionstring::Character", "kRepresentativeChars", m.representative_chars, integer);
    put_array(out, "::actionstring::LabelId", "kRepresentativeLabels", m.representative_labels, integer);
    put_array(out, "const char* const", "kLabelNames", m.label_names, c_string);
    auto or_null = [](bool present, const char* name) { return present ? std::string(name) : std::string("nullptr"); };
    out << "\nconstexpr ::actionstring::ModelView make_model() {\n"
        << "    ::actionstring::ModelView m{};\n"
        << "    m.joint_count = " << v.joint_count << ";\n"
        << "    m.root_joint = " << v.root_joint << ";\n"
        << "    m.left_hip_joint = " << v.left_hip_joint << ";\n"
        << "    m.right_hip_joint = " << v.right_hip_joint << ";\n"
        << "    m.up_axis = " << static_cast<int>(v.up_axis) << ";\n"
        << "    m.scale_mode = static_cast<::actionstring::ScaleMode>(" << static_cast<int>(v.scale_mode) << ");\n"
        << "    m.reference_scale = " << float_literal(v.reference_scale) << ";\n"
        << "    m.pose_joint_count = " << v.pose_joint_count << ";\n"
        << "    m.pose_joints = kPoseJoints;\n"
        << "    m.feature_dim = " << v.feature_dim << ";\n"
        << "    m.projection_mean = " << or_null(!m.projection_mean.empty(), "kProjectionMean") << ";\n"
        << "    m.projection_matrix = " << or_null(!m.projection_matrix.empty(), "kProjectionMatrix") << ";\n"
        << "    m.component_count = " << v.component_count << ";\n"
        << "    m.covariance = static_cast<::actionstring::Covariance>(" << static_cast<int>(v.covariance) << ");\n"
        << "    m.gmm_means = " << or_null(v.has_gmm(), "kGmmMeans") << ";\n    m.gmm_factors = " << or_null(v.has_gmm(), "kGmmFactors") << ";\n"
        << "    m.gmm_log_normalizers = " << or_null(v.has_gmm(), "kGmmLogNormalizers") << ";\n    m.gmm_log_weights = "
        << or_null(v.has_gmm(), "kGmmLogWeights") << ";\n"
        << "    m.node_count = " << v.node_count << ";\n"
        << "    m.node_centroids = kNodeCentroids;\n    m.node_children = kNodeChildren;\n    m.node_characters = kNodeCharacters;\n"
        << "    m.character_count = " << v.character_count << ";\n"
        << "    m.character_distances = kCharacterDistances;\n"
        << "    m.string_period_us = " << v.string_period_us << ";\n"
        << "    m.representative_count = " << v.representative_count << ";\n"
        << "    m.representative_offsets = kRepresentativeOffsets;\n"
        << "    m.representative_chars = kRepresentativeChars;\n"
        << "    m.representative_labels = kRepresentativeLabels;\n"
        << "    m.label_count = " << v.label_count << ";\n"
        << "    m.label_names = kLabelNames;\n"
        << "    m.variant = static_cast<::actionstring::MatchVariant>(" << static_cast<int>(v.variant) << ");\n"
        << "    m.normalization = static_cast<::actionstring::LengthNormalization>(" << static_cast<int>(v.normalization) << ");\n"
        << "    m.window_chars = " << v.window_chars << ";\n"
        << "    m.step_chars = " << v.step_chars << ";\n"
        << "    m.neighbours = " << v.neighbours << ";\n"
        << "    m.unknown_distance = " << float_literal(v.unknown_distance) << ";\n"
        << "    return m;\n}\n\n"
        << "/// The model. Its tables have static storage: any state object may point at it for ever.\n"
        << "inline constexpr ::actionstring::ModelView kModel = make_model();\n\n"
        << "/// Capacity that fits this model exactly.\n"
        << "using ModelCapacity = ::actionstring::Capacity<" << v.joint_count << ", " << v.pose_joint_count << ", " << v.feature_dim
        << ", " << std::max<int>(1, v.component_count) << ", " << v.representative_count << ", " << v.total_representative_chars() << ", "
        << v.max_open_windows() << ", " << (v.normalization == LengthNormalization::path ? "true" : "false") << ">;\n\n"
        << "}  // namespace " << ns << "\n";
    return out.str();
}

ConcatenatedStream concatenate_stream(const std::vector<StreamSegment>& segments) {
    ConcatenatedStream stream;
    if (segments.empty()) throw std::invalid_argument("a stream needs at least one clip");
    const std::size_t joints = segments.front().clip->joint_count();
    stream.joints = joints;
    auto& times_us = stream.times_us;
    auto& positions = stream.positions;
    double offset_s = 0.0;  // shifts each clip to start one frame period after the previous one
    for (const StreamSegment& segment : segments) {
        const Clip& clip = *segment.clip;
        if (clip.joint_count() != joints)
            throw std::invalid_argument(clip.source + ": " + std::to_string(clip.joint_count()) + " joints, the stream has " +
                                        std::to_string(joints));
        const double period = clip.frame_count() > 1 ? clip.duration() / static_cast<double>(clip.frame_count() - 1) : 1.0 / 120.0;
        const std::size_t frames =
            segment.max_seconds > 0 ? std::min(clip.frame_count(), static_cast<std::size_t>(segment.max_seconds / period) + 1)
                                    : clip.frame_count();
        if (frames == 0) continue;
        if (!times_us.empty()) offset_s = static_cast<double>(times_us.back()) * 1e-6 + period - clip.times.front();
        else offset_s = -clip.times.front();
        stream.segment_first_frame.push_back(static_cast<std::uint32_t>(times_us.size()));
        stream.segment_labels.push_back(segment.label);
        for (std::size_t f = 0; f < frames; ++f) {
            times_us.push_back(std::llround((clip.times[f] + offset_s) * 1e6));
            positions.insert(positions.end(), clip.frame(f), clip.frame(f) + joints * 3);
        }
    }
    if (times_us.empty()) throw std::invalid_argument("the stream has no frames");
    return stream;
}

std::string generate_stream_text(const std::vector<StreamSegment>& segments) {
    const ConcatenatedStream stream = concatenate_stream(segments);
    std::string text;
    for (std::size_t f = 0; f < stream.times_us.size(); ++f) {
        text += std::to_string(stream.times_us[f]);
        const float* frame = stream.frame(f);
        for (std::size_t k = 0; k < stream.joints * 3; ++k) text += ' ' + hex_float(frame[k]);
        text += '\n';
    }
    return text;
}

std::string generate_stream_header(const std::vector<StreamSegment>& segments, const std::string& ns,
                                   const std::string& command) {
    const ConcatenatedStream stream = concatenate_stream(segments);
    auto integer = [](auto x) { return std::to_string(static_cast<long long>(x)); };
    std::ostringstream out;
    out << "// DO NOT EDIT. Generated by `" << command << "`.\n"
        << "// A recorded stream replayed frame by frame by the firmware and its host twin.\n"
        << "// It holds dataset content: generate it at build time, never commit it.\n"
        << "#pragma once\n\n#include <cstdint>\n\n"
        << "// Lets a firmware place the (large) frame tables in a section of its choice.\n"
        << "#ifndef ACTIONSTRING_STREAM_SECTION\n#define ACTIONSTRING_STREAM_SECTION\n#endif\n\n"
        << "namespace " << ns << " {\n\n"
        << "inline constexpr std::uint32_t kJointCount = " << stream.joints << ";\n"
        << "inline constexpr std::uint32_t kFrameCount = " << stream.frame_count() << ";\n"
        << "inline constexpr std::uint32_t kSegmentCount = " << stream.segment_first_frame.size() << ";\n";
    put_array(out, "std::uint32_t", "kSegmentFirstFrame", stream.segment_first_frame, integer);
    put_array(out, "const char*", "kSegmentLabel", stream.segment_labels, c_string);
    put_array(out, "std::int64_t", "kFrameTimeUs", stream.times_us, integer, "ACTIONSTRING_STREAM_SECTION ");
    put_array(out, "float", "kFramePositions", stream.positions, float_literal, "ACTIONSTRING_STREAM_SECTION ");
    out << "\n}  // namespace " << ns << "\n";
    return out.str();
}

}  // namespace host
}  // namespace actionstring
