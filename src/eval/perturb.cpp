// Evaluated clips as another sensor or person would give them.
#include "eval/perturb.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "train/augment.hpp"
#include "train/settings.hpp"

namespace actionstring {
namespace host {

namespace {

// Draws from std::mt19937_64, whose output the standard fixes, with our own
// uniform and Gaussian transforms (the standard library's distributions differ
// between implementations), so a perturbed evaluation is the same everywhere.
class Draws {
public:
    Draws(std::uint64_t seed, std::uint64_t index) : rng_(mix(seed ^ mix(index + 0x9E3779B97F4A7C15ull))) {}
    /// Uniform in [0, 1).
    double uniform() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
    /// Standard normal (Box–Muller; the first value of each pair).
    double normal() {
        const double u = 1.0 - uniform();  // (0, 1]: its logarithm is finite
        const double v = uniform();
        return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
    }

private:
    // splitmix64's finaliser: nearby seeds and indices give unrelated streams.
    static std::uint64_t mix(std::uint64_t x) {
        x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
        x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
        return x ^ (x >> 31);
    }
    std::mt19937_64 rng_;
};

bool is_lost(const Clip& clip, std::size_t f) { return f < clip.lost.size() && clip.lost[f] != 0; }

// Every tracked frame rotated by `degrees` about the horizontal line through
// the mean root position along the mean horizontal hip direction. A clip
// without roles, tracked frames or a horizontal hip direction is unchanged.
void tilt(Clip& clip, double degrees) {
    const JointRoles& roles = clip.roles;
    if (!roles.complete()) return;
    const int up = clip.up_axis;
    double axis[3] = {0.0, 0.0, 0.0}, centre[3] = {0.0, 0.0, 0.0};
    std::size_t tracked = 0;
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        if (is_lost(clip, f)) continue;
        const float* frame = clip.frame(f);
        for (int a = 0; a < 3; ++a) {
            axis[a] += static_cast<double>(frame[3 * roles.right_hip + a]) - frame[3 * roles.left_hip + a];
            centre[a] += frame[3 * roles.root + a];
        }
        ++tracked;
    }
    axis[up] = 0.0;
    const double length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    if (tracked == 0 || !(length > 0.0)) return;
    for (double& v : axis) v /= length;
    for (double& v : centre) v /= static_cast<double>(tracked);
    // Rodrigues: v cos θ + (k × v) sin θ + k (k · v)(1 − cos θ), about the centre.
    const double theta = degrees * 3.14159265358979323846 / 180.0, c = std::cos(theta), s = std::sin(theta);
    for (std::size_t f = 0; f < clip.frame_count(); ++f) {
        if (is_lost(clip, f)) continue;
        float* frame = clip.frame(f);
        for (std::size_t j = 0; j < clip.joint_count(); ++j) {
            float* x = frame + 3 * j;
            const double v[3] = {x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]};
            const double along = axis[0] * v[0] + axis[1] * v[1] + axis[2] * v[2];
            const double cross[3] = {axis[1] * v[2] - axis[2] * v[1], axis[2] * v[0] - axis[0] * v[2],
                                     axis[0] * v[1] - axis[1] * v[0]};
            for (int a = 0; a < 3; ++a)
                x[a] = static_cast<float>(centre[a] + v[a] * c + cross[a] * s + axis[a] * along * (1.0 - c));
        }
    }
}

void resample(Clip& clip, double rate_hz) {
    const std::size_t n = clip.frame_count(), stride = clip.joint_count() * 3;
    if (n < 2 || stride == 0) return;
    const bool tracks_lost = !clip.lost.empty();
    std::vector<double> times;
    std::vector<float> positions;
    std::vector<std::uint8_t> lost;
    const double first = clip.times.front(), last = clip.times.back(), period = 1.0 / rate_hz;
    std::size_t i = 0;  // clip.times[i] <= t < clip.times[i + 1], or i = n − 1 at the end
    for (std::size_t k = 0;; ++k) {
        const double t = first + static_cast<double>(k) * period;
        if (t > last) break;
        while (i + 1 < n && clip.times[i + 1] <= t) ++i;
        const std::size_t j = std::min(i + 1, n - 1);
        const double span = clip.times[j] - clip.times[i];
        const double a = span > 0.0 ? (t - clip.times[i]) / span : 0.0;
        const bool gone = (is_lost(clip, i) && a < 1.0) || (is_lost(clip, j) && a > 0.0);
        times.push_back(t);
        lost.push_back(gone ? 1 : 0);
        const float* p = clip.frame(i);
        const float* q = clip.frame(j);
        for (std::size_t c = 0; c < stride; ++c)
            positions.push_back(
                gone ? 0.0f
                     : static_cast<float>((1.0 - a) * static_cast<double>(p[c]) + a * static_cast<double>(q[c])));
    }
    clip.times = std::move(times);
    clip.positions = std::move(positions);
    if (tracks_lost || std::find(lost.begin(), lost.end(), 1) != lost.end()) clip.lost = std::move(lost);
}

void drop_frames(Clip& clip, double drop, Draws& draws) {
    const std::size_t n = clip.frame_count(), stride = clip.joint_count() * 3;
    if (n < 3) return;
    std::size_t kept = 0;
    for (std::size_t f = 0; f < n; ++f) {
        const bool keep = f == 0 || f + 1 == n || draws.uniform() >= drop;
        if (!keep) continue;
        if (kept != f) {
            clip.times[kept] = clip.times[f];
            std::copy(clip.frame(f), clip.frame(f) + stride, clip.frame(kept));
            if (!clip.lost.empty()) clip.lost[kept] = clip.lost[f];
        }
        ++kept;
    }
    clip.times.resize(kept);
    clip.positions.resize(kept * stride);
    if (!clip.lost.empty()) clip.lost.resize(kept);
}

double number(const std::string& item, const std::string& text, double low, double high, const char* expected) {
    const std::optional<double> value = parse_real(text, low, high);
    if (!value) throw std::invalid_argument("--perturb: '" + item + "': expected " + expected);
    return *value;
}

}  // namespace

bool Perturbation::any() const noexcept {
    return scale != 1.0 || mirror || tilt_deg != 0.0 || noise_m > 0.0 || drop > 0.0 || rate_hz > 0.0 || jitter_s > 0.0;
}

std::string Perturbation::describe() const {
    if (!any()) return "none";
    std::vector<std::string> parts;
    auto add = [&parts](auto... pieces) {
        std::ostringstream out;
        (out << ... << pieces);
        parts.push_back(out.str());
    };
    if (rate_hz > 0.0) add("resampled to ", rate_hz, " Hz");
    if (mirror) add("mirrored");
    if (tilt_deg != 0.0) add("tilted ", tilt_deg, "°");
    if (scale != 1.0) add("scale ", scale);
    if (noise_m > 0.0) add("noise ", noise_m, " m");
    if (jitter_s > 0.0) add("timestamp jitter ±", jitter_s, " s");
    if (drop > 0.0) add(drop, " of the frames dropped");
    std::string text;
    for (const std::string& part : parts) text += (text.empty() ? "" : ", ") + part;
    return text + " (seed " + std::to_string(seed) + ")";
}

Perturbation parse_perturbation(const std::string& spec) {
    Perturbation p;
    std::set<std::string> seen;
    std::size_t at = 0;
    if (spec.empty()) throw std::invalid_argument("--perturb: expected name=value items, e.g. scale=0.7,noise=0.01");
    while (at <= spec.size()) {
        std::size_t comma = spec.find(',', at);
        if (comma == std::string::npos) comma = spec.size();
        const std::string item = spec.substr(at, comma - at);
        at = comma + 1;
        const std::size_t equals = item.find('=');
        if (equals == std::string::npos)
            throw std::invalid_argument(
                "--perturb: '" + item +
                "': expected name=value (scale, mirror, tilt, noise, drop, rate, jitter, seed)");
        const std::string name = item.substr(0, equals), value = item.substr(equals + 1);
        if (!seen.insert(name).second) throw std::invalid_argument("--perturb: '" + name + "' is given twice");
        if (name == "scale") p.scale = number(item, value, 0.01, 100.0, "a factor from 0.01 to 100");
        else if (name == "mirror") {
            const double flag = number(item, value, 0.0, 1.0, "0 or 1");
            if (flag != 0.0 && flag != 1.0) throw std::invalid_argument("--perturb: '" + item + "': expected 0 or 1");
            p.mirror = flag == 1.0;
        } else if (name == "tilt") p.tilt_deg = number(item, value, -90.0, 90.0, "degrees from -90 to 90");
        else if (name == "noise") p.noise_m = number(item, value, 0.0, 1.0, "metres from 0 to 1");
        else if (name == "drop") p.drop = number(item, value, 0.0, 0.99, "a probability from 0 to 0.99");
        else if (name == "rate") p.rate_hz = number(item, value, 0.1, 10000.0, "frames per second from 0.1 to 10000");
        else if (name == "jitter") p.jitter_s = number(item, value, 0.0, 1.0, "seconds from 0 to 1");
        else if (name == "seed") {
            const double seed = number(item, value, 0.0, 9007199254740992.0, "a whole number");
            if (seed != std::floor(seed))
                throw std::invalid_argument("--perturb: '" + item + "': expected a whole number");
            p.seed = static_cast<std::uint64_t>(seed);
        } else
            throw std::invalid_argument(
                "--perturb: '" + name +
                "' is not a perturbation (scale, mirror, tilt, noise, drop, rate, jitter, seed)");
        if (comma == spec.size()) break;
    }
    return p;
}

void perturb_clip(Clip& clip, const Perturbation& p, std::uint64_t index) {
    if (!p.any()) return;
    Draws draws(p.seed, index);
    if (p.rate_hz > 0.0) resample(clip, p.rate_hz);
    const std::size_t n = clip.frame_count(), stride = clip.joint_count() * 3;
    if (p.mirror) clip = mirror_clip(clip);
    if (p.tilt_deg != 0.0) tilt(clip, p.tilt_deg);
    if (p.scale != 1.0)
        for (float& v : clip.positions) v = static_cast<float>(static_cast<double>(v) * p.scale);
    if (p.noise_m > 0.0)
        for (std::size_t f = 0; f < n; ++f) {
            if (is_lost(clip, f)) continue;
            float* frame = clip.frame(f);
            for (std::size_t c = 0; c < stride; ++c)
                frame[c] = static_cast<float>(static_cast<double>(frame[c]) + p.noise_m * draws.normal());
        }
    if (p.jitter_s > 0.0 && n > 0) {
        // Kept in order and not before the clip's first frame (times may repeat).
        const double first = clip.times.front();
        for (double& t : clip.times) t = std::max(first, t + p.jitter_s * (2.0 * draws.uniform() - 1.0));
        for (std::size_t f = 1; f < n; ++f) clip.times[f] = std::max(clip.times[f], clip.times[f - 1]);
    }
    if (p.drop > 0.0) drop_frames(clip, p.drop, draws);
}

}  // namespace host
}  // namespace actionstring
