// `actionstring annotate --live`: frames from standard input or a UDP port.
#include "live.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/json.hpp"
#include "common/time.hpp"
#include "io/formats.hpp"
#include "run/skeleton.hpp"
#include "run/state.hpp"
#include "run/stream_labels.hpp"

namespace actionstring {
namespace cli {
namespace {

// Lines from standard input, or from the datagrams of a loopback UDP socket.
class LineSource {
public:
    explicit LineSource(const LiveSource& source) : source_(source) {
        if (source_.udp_port == 0) return;
        socket_ = ::socket(AF_INET, SOCK_DGRAM, 0);
        if (socket_ < 0) throw std::runtime_error("cannot open a UDP socket");
        // The socket's receive buffer is the bounded queue: datagrams beyond it are dropped by the system.
        const int buffer = 256 * 1024;
        ::setsockopt(socket_, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
        sockaddr_in address{};
        address.sin_family = AF_INET;
        address.sin_port = htons(static_cast<std::uint16_t>(source_.udp_port));
        address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        if (::bind(socket_, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0)
            throw std::runtime_error("cannot listen on 127.0.0.1:" + std::to_string(source_.udp_port) + " (" +
                                     std::strerror(errno) + ")");
        std::fprintf(stderr, "actionstring annotate: listening on udp 127.0.0.1:%d\n", source_.udp_port);
        std::fflush(stderr);
    }
    ~LineSource() {
        if (socket_ >= 0) ::close(socket_);
    }
    LineSource(const LineSource&) = delete;
    LineSource& operator=(const LineSource&) = delete;

    /// The next line, or false at the end of the input (or the idle timeout).
    bool next(std::string& line) {
        if (source_.udp_port == 0) {
            line.clear();
            int c = 0;
            while ((c = std::getc(stdin)) != EOF && c != '\n') {
                if (line.size() < max_line) line.push_back(static_cast<char>(c));
            }
            if (c == EOF && line.empty()) return false;
            if (!line.empty() && line.back() == '\r') line.pop_back();
            return true;
        }
        while (pending_.empty()) {
            pollfd ready{socket_, POLLIN, 0};
            const int timeout_ms = source_.idle_timeout_s > 0 ? static_cast<int>(source_.idle_timeout_s * 1000) : -1;
            const int n = ::poll(&ready, 1, timeout_ms);
            if (n == 0) return false;  // idle: the stream is over
            if (n < 0) {
                if (errno == EINTR) continue;
                return false;
            }
            std::vector<char> datagram(65536);
            const ssize_t got = ::recv(socket_, datagram.data(), datagram.size(), 0);
            if (got <= 0) continue;
            std::string text(datagram.data(), static_cast<std::size_t>(got));
            std::size_t begin = 0;
            while (begin <= text.size()) {
                std::size_t end = text.find('\n', begin);
                if (end == std::string::npos) end = text.size();
                std::string one = text.substr(begin, end - begin);
                if (!one.empty() && one.back() == '\r') one.pop_back();
                if (!one.empty()) pending_.push_back(one);
                begin = end + 1;
            }
        }
        line = pending_.front();
        pending_.erase(pending_.begin());
        return true;
    }

private:
    static constexpr std::size_t max_line = 1 << 20;
    LiveSource source_;
    int socket_ = -1;
    std::vector<std::string> pending_;
};

void print_line(host::JsonWriter& out) {
    std::string line = out.str();
    while (!line.empty() && line.back() == '\n') line.pop_back();
    std::printf("%s\n", line.c_str());
}

}  // namespace

int run_live(const host::ModelData& model, const AnnotatorConfig& config, const host::ReadOptions& read,
             const LiveSource& source) {
    const ModelView view = model.view();
    LineSource lines(source);
    std::string line;
    std::size_t line_number = 0;
    // The header: the first line that is not empty or a comment.
    while (lines.next(line)) {
        ++line_number;
        if (!line.empty() && line[0] != '#') break;
    }
    if (line.empty() || line[0] == '#') {
        std::fprintf(stderr, "actionstring annotate: no header line on the input\n");
        return 1;
    }
    const host::JointCsvLayout layout("<live>", line, line_number, read);
    for (const std::string& note : layout.notes()) std::fprintf(stderr, "actionstring annotate: %s\n", note.c_str());
    double unit = layout.time_unit_s();
    if (layout.time_column() >= 0 && !(unit > 0)) {
        unit = 1.0;
        std::fprintf(stderr, "actionstring annotate: timestamps taken as seconds (give --time-unit s|ms|us)\n");
    }
    // The model's joints from the header's, by name: a one-frame clip whose
    // x coordinates are the header's joint indices, put in the model's order.
    host::Clip probe;
    probe.source = "<live>";
    probe.joint_names = layout.joint_names();
    probe.times = {0.0};
    for (std::size_t j = 0; j < probe.joint_names.size(); ++j)
        probe.positions.insert(probe.positions.end(), {static_cast<float>(j), 1.0f, 1.0f});
    host::conform_to_model(view, probe);
    std::vector<std::size_t> from(view.joint_count);
    for (std::size_t j = 0; j < view.joint_count; ++j) from[j] = static_cast<std::size_t>(probe.positions[3 * j]);

    host::Stateful<Annotator> annotator;
    const Status status = annotator.init(view, config);
    if (status != Status::ok) throw std::invalid_argument(host::annotator_refusal(view, config, status));
    std::vector<float> row(3 * layout.joint_names().size()), frame(3u * view.joint_count);
    std::size_t frames = 0, skipped = 0, rejected = 0;
    int shown = -2;
    auto label_name = [&](LabelId id) { return id == unknown_label ? std::string("unknown") : model.label_names[id]; };
    auto print_events = [&]() {
        for (std::size_t i = 0; i < annotator->event_count(); ++i) {
            const ActionEvent& e = annotator->event(i);
            host::JsonWriter out;
            out.begin_object()
                .field("event", e.kind == ActionEvent::Kind::started ? "started" : "ended")
                .field("label", label_name(e.label))
                .field("start", host::us_to_seconds(e.start_time_us))
                .field("end", host::us_to_seconds(e.end_time_us))
                .field("confidence", static_cast<double>(e.confidence))
                .end_object();
            print_line(out);
        }
    };
    // A settled label that differs from the last one shown, printed; returns whether it was.
    auto show = [&](LabelId label, std::int64_t time_us) {
        if (static_cast<int>(label) == shown) return false;
        shown = label;
        host::JsonWriter out;
        out.begin_object().field("settled", label_name(label)).field("time", host::us_to_seconds(time_us)).end_object();
        print_line(out);
        return true;
    };
    // The labels an ended stream's last characters took when it ended (a restart or the flush).
    auto show_flushed = [&]() {
        bool wrote = false;
        for (std::size_t i = 0; i < annotator->flushed_characters(); ++i)
            wrote = show(annotator->flushed_label(i), annotator->flushed_label_time_us(i)) || wrote;
        return wrote;
    };
    // A live stream's unit cannot be read off a whole recording: metres unless --length-unit says.
    const float metres_per_unit = read.length_scale > 0 ? static_cast<float>(read.length_scale) : 1.0f;
    std::string error;
    while (lines.next(line)) {
        ++line_number;
        if (line.empty() || line[0] == '#') continue;
        double raw_time = 0;
        bool untracked = false;  // a lost frame: zeros, which the annotator reports as tracking lost
        if (!layout.parse_row(line, raw_time, row.data(), error, untracked)) {
            if (++skipped <= 10)
                std::fprintf(stderr, "actionstring annotate: line %zu skipped: %s\n", line_number, error.c_str());
            continue;
        }
        const double time_s = layout.time_column() >= 0 ? raw_time * unit
                                                        : static_cast<double>(frames) / read.frame_rate_hz;
        for (std::size_t j = 0; j < view.joint_count; ++j)
            for (std::size_t a = 0; a < 3; ++a) frame[3 * j + a] = row[3 * from[j] + a] * metres_per_unit;
        const FrameResult r = annotator->push_frame(host::seconds_to_us(time_s), frame.data());
        ++frames;
        if (r.status != Status::ok && r.status != Status::stream_restarted) ++rejected;
        bool wrote = show_flushed();  // a restart: the ended stream's last labels first
        // Each character the frame settled, in order: with early settling a frame may
        // settle a run of them, whose first label change must not be lost.
        const std::uint64_t last = annotator->settled_character();
        for (std::uint64_t c = last + 1 - r.characters_settled; r.characters_settled > 0 && c <= last; ++c)
            wrote = show(annotator->settled_label(c), annotator->label_time_us(c)) || wrote;
        print_events();
        if (wrote || r.events > 0) std::fflush(stdout);
    }
    annotator->flush();
    show_flushed();
    print_events();
    std::fflush(stdout);
    std::fprintf(stderr,
                 "actionstring annotate: %zu frames, %zu malformed lines skipped, %zu frames rejected by the "
                 "annotator\n",
                 frames, skipped, rejected);
    return 0;
}

}  // namespace cli
}  // namespace actionstring
