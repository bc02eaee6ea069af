// The reliability probe: hostile inputs against the readers, the model loader,
// the runtime and the command line, each case in its own process with a time
// limit, sorted into outcomes:
//   crash           the process died of a signal (a sanitizer abort included)
//   hang            it outlived its time limit
//   silent garbage  it accepted the input and returned something unusable:
//                   a non-finite position, a label out of range, exit 0 from
//                   a command given nonsense
//   unclear error   it refused the input without naming the file (readers:
//                   "file:line: …" or "file: …"), with an exception that is
//                   not a ReadError, or (commands) without "actionstring CMD:"
// Mutated files are built in memory from the datasets in ../shared/data and
// never written to the repository.
//   actionstring_probe CLI [--cases N] [--seed S] [--markdown FILE]
// Exits 1 when any case lands outside "accepted" or "clear refusal"; 77 without data.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "actionstring/annotator.hpp"
#include "run/state.hpp"
#include "io/clip_list.hpp"
#include "io/formats.hpp"
#include "io/text.hpp"
#include "model/artifact.hpp"
#include "toy/toy.hpp"

using namespace actionstring;
using namespace actionstring::host;

namespace {

enum Outcome { accepted = 0, refused = 10, garbage = 11, unclear = 12, crash = 20, hang = 21 };

struct Tally {
    explicit Tally(std::string description) : what(std::move(description)) {}
    std::string what;
    std::uint64_t tried = 0, crashes = 0, hangs = 0, garbage = 0, unclear = 0, accepted = 0, refused = 0;
    std::vector<std::string> examples;  // the first few cases of each bad outcome
};

// Runs `body` in a child process with a time limit and memory cap; the
// child's exit code is its outcome.
Outcome isolated(const std::function<Outcome()>& body, unsigned seconds) {
    std::fflush(stdout);
    std::fflush(stderr);
    const pid_t pid = fork();
    if (pid < 0) {
        std::perror("fork");
        std::exit(2);
    }
    if (pid == 0) {
        alarm(seconds);
        const rlimit memory{3ull << 30, 3ull << 30};  // 3 GiB: a runaway allocation fails instead of swapping
        setrlimit(RLIMIT_AS, &memory);
        std::_Exit(body());
    }
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFSIGNALED(status)) return WTERMSIG(status) == SIGALRM ? hang : crash;
    return static_cast<Outcome>(WEXITSTATUS(status));
}

void record(Tally& t, Outcome o, const std::string& description) {
    ++t.tried;
    switch (o) {
        case accepted: ++t.accepted; return;
        case refused: ++t.refused; return;
        case garbage: ++t.garbage; break;
        case unclear: ++t.unclear; break;
        case crash: ++t.crashes; break;
        case hang: ++t.hangs; break;
    }
    if (t.examples.size() < 5) t.examples.push_back(description);
}

// ---- mutations -------------------------------------------------------------------

const char* const kExtremes[] = {"1e308", "-1e308", "nan", "inf", "-inf", "1e-300", "0", "-1", "2147483648",
                                 "99999999999999999999", "4294967296", "-0", "1e7", "0x1p+1023", "", "x"};

// One random mutation of a text: a byte, a line, a number or the length.
std::string mutate(const std::string& text, std::mt19937_64& rng, std::string& how) {
    std::string out = text;
    if (out.empty()) return "x";
    auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
    auto line_bounds = [&](std::size_t at) {
        const std::size_t begin = out.rfind('\n', at) == std::string::npos ? 0 : out.rfind('\n', at) + 1;
        const std::size_t end = std::min(out.find('\n', at), out.size());
        return std::make_pair(begin, end);
    };
    switch (pick(7)) {
        case 0: {  // flip a byte
            const std::size_t at = pick(out.size());
            out[at] = static_cast<char>(out[at] ^ static_cast<char>(1 + pick(255)));
            how = "byte " + std::to_string(at) + " changed";
            break;
        }
        case 1: {  // truncate
            const std::size_t at = pick(out.size());
            out.resize(at);
            how = "truncated at byte " + std::to_string(at);
            break;
        }
        case 2: {  // delete a line
            const auto [b, e] = line_bounds(pick(out.size()));
            out.erase(b, std::min(e + 1, out.size()) - b);
            how = "a line deleted";
            break;
        }
        case 3: {  // duplicate a line
            const auto [b, e] = line_bounds(pick(out.size()));
            out.insert(b, out.substr(b, e - b) + "\n");
            how = "a line repeated";
            break;
        }
        case 4:
        case 5: {  // a number replaced by an extreme
            std::vector<std::pair<std::size_t, std::size_t>> numbers;
            for (std::size_t i = 0; i < out.size() && numbers.size() < 4096;) {
                if (std::isdigit(static_cast<unsigned char>(out[i])) || (out[i] == '-' && i + 1 < out.size() &&
                                                                          std::isdigit(static_cast<unsigned char>(out[i + 1])))) {
                    std::size_t j = i + 1;
                    while (j < out.size() && (std::isdigit(static_cast<unsigned char>(out[j])) || out[j] == '.' ||
                                              out[j] == 'e' || out[j] == '-' || out[j] == '+'))
                        ++j;
                    numbers.emplace_back(i, j - i);
                    i = j;
                } else {
                    ++i;
                }
            }
            if (numbers.empty()) return mutate(text, rng, how);
            const auto [at, length] = numbers[pick(numbers.size())];
            const std::string extreme = kExtremes[pick(sizeof kExtremes / sizeof *kExtremes)];
            out.replace(at, length, extreme);
            how = "a number replaced by '" + extreme + "'";
            break;
        }
        default: {  // garbage inserted
            const std::size_t at = pick(out.size());
            std::string junk(1 + pick(40), ' ');
            for (char& c : junk) c = static_cast<char>(pick(256));
            out.insert(at, junk);
            how = "garbage inserted at byte " + std::to_string(at);
            break;
        }
    }
    return out;
}

bool finite_clip(const Clip& clip) {
    if (clip.positions.size() != clip.frame_count() * clip.joint_count() * 3) return false;
    for (float v : clip.positions)
        if (!std::isfinite(v)) return false;
    for (std::size_t f = 0; f < clip.times.size(); ++f)
        if (!std::isfinite(clip.times[f]) || (f > 0 && clip.times[f] < clip.times[f - 1])) return false;
    return true;
}

// A reader's outcome on one input: a usable clip, or a ReadError naming the file.
Outcome reader_outcome(const std::string& name, const std::function<void()>& read) {
    try {
        read();
        return accepted;
    } catch (const ReadError& error) {
        const std::string message = error.what();
        return message.rfind(name + ":", 0) == 0 && message.size() > name.size() + 8 ? refused : unclear;
    } catch (...) {
        return unclear;
    }
}

// ---- the cases -------------------------------------------------------------------

struct Sample {
    std::string name, text;
    std::function<void(const std::string&, const std::string&)> read;  // throws; aborts on garbage
};

void check_clip(const Clip& clip) {
    if (!finite_clip(clip)) std::_Exit(garbage);
}

std::vector<Sample> motion_samples(const std::string& data) {
    std::vector<Sample> samples;
    auto add = [&](const std::string& path, std::function<void(const std::string&, const std::string&)> read) {
        try {
            samples.push_back({path.substr(path.find_last_of('/') + 1), read_file(path), std::move(read)});
        } catch (const ReadError&) {
        }
    };
    const auto hdm = read_clip_list(data + "/hdm05/val.tsv");
    const std::string asf_path = hdm.front().skeleton;
    const AsfSkeleton skeleton = parse_asf(asf_path, read_file(asf_path));
    add(asf_path, [](const std::string& n, const std::string& t) { parse_asf(n, t); });
    for (std::size_t i = 0; i < hdm.size(); i += 11)
        add(hdm[i].path, [skeleton](const std::string& n, const std::string& t) { check_clip(parse_amc(n, t, skeleton)); });
    const auto msr = read_clip_list(data + "/msr-action3d/test.tsv");
    for (std::size_t i = 0; i < msr.size(); i += 90)
        add(msr[i].path, [](const std::string& n, const std::string& t) { check_clip(parse_msr_skeleton(n, t)); });
    for (const char* file : {"joints_s01_e01.txt", "joints_s04_e02.txt"})
        add(data + "/utkinect/" + file, [](const std::string& n, const std::string& t) { check_clip(parse_utkinect(n, t)); });
    add(data + "/utkinect/actionLabel.txt",
        [](const std::string& n, const std::string& t) { parse_utkinect_labels(n, t); });
    add(data + "/hdm05/train.tsv", [](const std::string& n, const std::string& t) { parse_clip_list(n, t, "."); });
    for (const char* file : {"002_01.bvh"})
        add(data + "/bvh/" + file, [](const std::string& n, const std::string& t) { check_clip(parse_bvh(n, t)); });
    return samples;
}

void probe_files(const std::string& data, int cases, std::mt19937_64& rng, Tally& tally) {
    const std::vector<Sample> samples = motion_samples(data);
    for (int c = 0; c < cases; ++c) {
        const Sample& sample = samples[static_cast<std::size_t>(c) % samples.size()];
        std::string how;
        const std::string text = mutate(sample.text, rng, how);
        const Outcome o = isolated([&] { return reader_outcome(sample.name, [&] { sample.read(sample.name, text); }); }, 20);
        record(tally, o, sample.name + ": " + how);
    }
}

// A loaded model must be one the runtime accepts and streams with labels in range.
Outcome model_outcome(const std::string& text, const std::vector<float>& frame) {
    try {
        const ModelData model = parse_model("probe.model", text);
        const ModelView view = model.view();
        Stateful<Annotator> annotator;
        AnnotatorConfig config = annotator_config(view);
        config.window_rule = true;
        // A valid model that asks for more state than the probe allocates counts as accepted.
        if (Annotator::required_bytes(view, config) > (std::size_t{256} << 20)) return accepted;
        const Status status = annotator.init(view, config);
        if (status == Status::model_exceeds_capacity) return accepted;
        if (status != Status::ok) return garbage;
        std::vector<float> positions(3u * view.joint_count);
        for (std::size_t k = 0; k < positions.size(); ++k) positions[k] = frame[k % frame.size()];
        for (int step = 0; step < 120; ++step) {
            positions[0] += 0.01f;
            annotator->push_frame(static_cast<std::int64_t>(step) * 8333, positions.data());
            const LabelId label = annotator->live_label();
            if (label != unknown_label && label >= view.label_count) return garbage;
            if (!std::isfinite(annotator->confidence())) return garbage;
        }
        return accepted;
    } catch (const ReadError& error) {
        return std::string(error.what()).rfind("probe.model", 0) == 0 ? refused : unclear;
    } catch (...) {
        return unclear;
    }
}

void probe_models(const std::string& model_path, int cases, std::mt19937_64& rng, Tally& tally) {
    const std::string artifact = read_file(model_path);
    const std::size_t body_start = artifact.find('\n', artifact.find('\n') + 1) + 1;
    const std::string body = artifact.substr(body_start);
    const ModelData original = parse_model(model_path, artifact);
    std::vector<float> frame;
    for (std::size_t j = 0; j < original.joint_count; ++j)
        for (int k = 0; k < 3; ++k) frame.push_back(0.1f * static_cast<float>((j * 3 + static_cast<std::size_t>(k)) % 9) - 0.4f);
    for (int c = 0; c < cases; ++c) {
        std::string how;
        const std::string mutated = mutate(body, rng, how);
        // Half keep a valid checksum, so validation, not the checksum, must refuse them.
        char line[64];
        std::snprintf(line, sizeof line, "checksum fnv1a64 %016llx\n",
                      static_cast<unsigned long long>(c % 2 == 0 ? fnv1a64(mutated) : fnv1a64(body)));
        const std::string text = artifact.substr(0, artifact.find('\n') + 1) + line + mutated;
        const Outcome o = isolated([&] { return model_outcome(text, frame); }, 20);
        record(tally, o, std::string(c % 2 == 0 ? "valid checksum, " : "") + how);
    }
}

// Adversarial timestamps and frames through the host annotator.
void probe_streams(const std::string& model_path, int cases, std::mt19937_64& rng, Tally& tally) {
    const ModelData model = load_model(model_path);
    const ModelView view = model.view();
    for (int c = 0; c < cases; ++c) {
        const std::uint64_t seed = rng();
        const Outcome o = isolated(
            [&]() -> Outcome {
                std::mt19937_64 r(seed);
                Stateful<Annotator> annotator;
                AnnotatorConfig config;
                config.window_rule = true;
                config.max_gap_us = std::uniform_int_distribution<std::int64_t>(100000, 60000000)(r);
                if (annotator.init(view, config) != Status::ok) return garbage;
                std::vector<float> frame(3u * view.joint_count);
                std::int64_t t = std::uniform_int_distribution<std::int64_t>(INT64_MIN / 2, INT64_MAX / 2)(r);
                for (int f = 0; f < 3000; ++f) {
                    switch (r() % 12) {
                        case 0: t = static_cast<std::int64_t>(r()); break;                // anywhere
                        case 1: t -= static_cast<std::int64_t>(r() % 100000000000); break;  // far back
                        case 2: t += static_cast<std::int64_t>(r() % 100000000000); break;  // far ahead
                        case 3: break;                                                     // repeated
                        default: t += 8333; break;
                    }
                    for (float& v : frame) v = std::uniform_real_distribution<float>(-1.0f, 1.0f)(r);
                    switch (r() % 16) {
                        case 0: frame[r() % frame.size()] = std::nanf(""); break;
                        case 1: std::fill(frame.begin(), frame.end(), 0.0f); break;
                        case 2: frame[r() % frame.size()] = 1e30f; break;
                        case 3: frame[r() % frame.size()] = -std::numeric_limits<float>::infinity(); break;
                        default: break;
                    }
                    const FrameResult result = annotator->push_frame(t, frame.data());
                    if (result.characters > max_ticks_per_frame) return garbage;
                    const LabelId live = annotator->live_label(), window = annotator->label();
                    if (live != unknown_label && live >= view.label_count) return garbage;
                    if (window != unknown_label && window >= view.label_count) return garbage;
                    if (!std::isfinite(annotator->confidence())) return garbage;
                }
                return accepted;
            },
            20);
        record(tally, o, "stream seed " + std::to_string(seed));
    }
}

// The command line given nonsense: it must refuse with "actionstring CMD: …" and a non-zero exit.
void probe_cli(const std::string& cli, const std::string& data, const std::string& model_path, Tally& tally) {
    const std::string work = "probe_cli";
    std::system(("mkdir -p " + work).c_str());
    write_file(work + "/empty.csv", "");
    write_file(work + "/bad.model", "actionstring-model 2\nchecksum fnv1a64 0\n");
    write_file(work + "/list.tsv", "path\tlabel\tsubject\nmissing.csv\ta\ts\n");
    const std::string utk = data + "/utkinect/joints_s01_e01.txt";
    const std::vector<std::pair<std::string, std::string>> cases{
        {"info", "info " + work},
        {"info", "info " + work + "/absent.bvh"},
        {"info", "info " + work + "/empty.csv"},
        {"info", "info --rate -5 " + utk},
        {"info", "info --rate abc " + utk},
        {"info", "info"},
        {"train", "train --clips " + work + "/list.tsv --out " + work + "/m.model"},
        {"train", "train --clips " + data + "/hdm05/train.tsv --components 999 --out " + work + "/m.model"},
        {"train", "train --clips " + data + "/hdm05/train.tsv --epsilon -1 --out " + work + "/m.model"},
        // A fraction where a count is due is refused, not truncated (it used to train with --pca 2).
        {"train", "train --clips " + data + "/hdm05/train.tsv --no-tune --pca 2.5 --out " + work + "/m.model"},
        {"train", "train --clips " + data +
                      "/hdm05/train.tsv --no-tune --exemplars 4 --exemplar-weight 1 "
                      "--exemplar-dims 99 --out " +
                      work + "/m.model"},
        {"train", "train --clips " + data + "/hdm05/train.tsv --config " + work + " --out " + work + "/m.model"},
        {"train",
         "train --clips " + data + "/hdm05/train.tsv --roles root,lhipjoint,lhipjoint --out " + work + "/m.model"},
        {"train",
         "train --clips " + data + "/hdm05/train.tsv --out /nonexistent/dir/m.model --string-rate 1 --sigma 0"},
        {"codegen", "codegen " + work + "/bad.model --out " + work + "/h.hpp"},
        {"codegen", "codegen " + model_path + " --out " + work + "/h.hpp --namespace a:b"},
        {"codegen", "codegen " + model_path + " --out " + work + "/h.hpp --namespace int"},
        {"codegen", "codegen " + model_path + " --out /nonexistent/dir/h.hpp"},
        {"codegen", "codegen " + work + " --out " + work + "/h.hpp"},
        {"eval", "eval --model " + model_path + " --clips " + work + "/list.tsv"},
        {"eval", "eval --model " + work + "/bad.model --clips " + data + "/hdm05/val.tsv"},
        {"eval", "eval --model " + model_path + " --clips " + data + "/msr-action3d/test.tsv"},
        {"eval", "eval --model " + model_path + " --clips " + data + "/hdm05/val.tsv --settle 99"},
        {"eval", "eval --model " + model_path + " --clips " + data + "/hdm05/val.tsv --unknown-cost -1"},
        {"eval", "eval --model " + model_path + " --clips " + data + "/hdm05/val.tsv --seed 1.5"},
        {"annotate", "annotate --model " + model_path + " " + utk},
        {"annotate", "annotate --model " + model_path + " " + work},
        {"annotate", "annotate --model " + model_path + " " + work + "/empty.csv"},
        {"annotate", "annotate --model " + model_path + " --segment-penalty nan " + utk},
        {"annotate", "annotate --model " + model_path},
        {"stream-table", "stream-table --clips " + data + "/hdm05/val.tsv --first 999 --out " + work + "/s.hpp"},
        {"stream-table", "stream-table --clips " + data + "/hdm05/val.tsv --count 2.5 --out " + work + "/s.hpp"},
        {"info", "info --up 1.5 " + utk},
        {"stream-table", "stream-table --clips " + data + "/hdm05/val.tsv --namespace 'a b' --out " + work + "/s.hpp"},
        {"interval-list", "interval-list --utkinect " + work + "/empty.csv --out " + work + "/l.tsv"},
        {"interval-list",
         "interval-list --utkinect " + data + "/utkinect/actionLabel.txt --subjects s99 --out " + work + "/l.tsv"},
        {"nonsense", "frobnicate"},
    };
    for (const auto& [command, arguments] : cases) {
        const std::string log = work + "/stderr.txt";
        const int status = std::system(("timeout 120 " + cli + " " + arguments + " >/dev/null 2>" + log).c_str());
        const std::string message = read_file(log);
        Outcome o = refused;
        if (WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) >= 128)) o = crash;
        else if (WIFEXITED(status) && WEXITSTATUS(status) == 124) o = hang;
        else if (WIFEXITED(status) && WEXITSTATUS(status) == 0) o = garbage;
        else if (message.find("actionstring") == std::string::npos || message.size() < 20) o = unclear;
        record(tally, o, arguments + " → " + message.substr(0, 160));
    }
    std::system(("rm -rf " + work).c_str());
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::fprintf(stderr, "usage: actionstring_probe CLI [--cases N] [--seed S] [--markdown FILE]\n");
        return 2;
    }
    const std::string cli = argv[1];
    int cases = 600;
    std::uint64_t seed = 1;
    std::string markdown;
    for (int i = 2; i + 1 < argc; i += 2) {
        const std::string arg = argv[i];
        if (arg == "--cases") cases = std::atoi(argv[i + 1]);
        else if (arg == "--seed") seed = std::strtoull(argv[i + 1], nullptr, 10);
        else if (arg == "--markdown") markdown = argv[i + 1];
    }
    const char* env = std::getenv("ACTIONSTRING_DATA");
    const std::string data = env != nullptr ? env : std::string(ACTIONSTRING_SOURCE_DIR) + "/../shared/data";
    if (std::system(("test -f " + data + "/hdm05/val.tsv -a -f " + data + "/msr-action3d/test.tsv").c_str()) != 0) {
        std::printf("SKIPPED: the probe mutates the datasets in %s, which are absent (set ACTIONSTRING_DATA)\n",
                    data.c_str());
        return 77;
    }
    // Real models to mutate and stream through, on HDM05: the committed example's
    // settings (no GMM; bone lengths, velocity) and the paper's GMM model, so
    // every table of a model is mutated.
    const std::string model_path = "probe_hdm05.model", gmm_model_path = "probe_hdm05_gmm.model";
    for (const auto& [config, path] : {std::pair<std::string, std::string>{"hdm05.config", model_path},
                                       std::pair<std::string, std::string>{"hdm05-gmm.config", gmm_model_path}}) {
        const std::string train = cli + " train --clips " + data + "/hdm05/train.tsv --config " +
                                  std::string(ACTIONSTRING_SOURCE_DIR) + "/models/" + config + " --out " + path +
                                  " >/dev/null 2>&1";
        if (std::system(train.c_str()) != 0) {
            std::fprintf(stderr, "actionstring_probe: training the probe model (models/%s) failed\n", config.c_str());
            return 1;
        }
    }
    std::mt19937_64 rng(seed);
    std::vector<Tally> tallies{Tally("mutated motion files, lists and label files"),
                               Tally("mutated models (half with a valid checksum)"),
                               Tally("adversarial timestamps and frames (3,000 frames each)"),
                               Tally("command-line misuse")};
    probe_files(data, cases, rng, tallies[0]);
    probe_models(model_path, cases / 4, rng, tallies[1]);
    probe_models(gmm_model_path, cases / 4, rng, tallies[1]);
    probe_streams(model_path, cases / 40, rng, tallies[2]);
    probe_streams(gmm_model_path, cases / 40, rng, tallies[2]);
    probe_cli(cli, data, model_path, tallies[3]);
    std::remove(model_path.c_str());
    std::remove(gmm_model_path.c_str());

    std::string table =
        "| cases | tried | accepted | refused clearly | crashes | hangs | silent garbage | unclear errors |\n"
        "|---|---:|---:|---:|---:|---:|---:|---:|\n";
    bool clean = true;
    for (const Tally& t : tallies) {
        char row[256];
        std::snprintf(row, sizeof row, "| %s | %llu | %llu | %llu | %llu | %llu | %llu | %llu |\n", t.what.c_str(),
                      static_cast<unsigned long long>(t.tried), static_cast<unsigned long long>(t.accepted),
                      static_cast<unsigned long long>(t.refused), static_cast<unsigned long long>(t.crashes),
                      static_cast<unsigned long long>(t.hangs), static_cast<unsigned long long>(t.garbage),
                      static_cast<unsigned long long>(t.unclear));
        table += row;
        clean = clean && t.crashes + t.hangs + t.garbage + t.unclear == 0;
    }
    std::printf("%s", table.c_str());
    for (const Tally& t : tallies)
        for (const std::string& example : t.examples) std::printf("  %s: %s\n", t.what.c_str(), example.c_str());
    if (!markdown.empty()) write_file(markdown, table);
    return clean ? 0 : 1;
}
