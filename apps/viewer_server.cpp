#include "viewer_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "ladarsim/dataset/exr_file.h"
#include "ladarsim/dataset/frame_io.h"
#include "ladarsim/core/input_error.h"

namespace ladarsim::apps {

namespace {

namespace fs = std::filesystem;

struct Response {
    int status = 200;
    std::string type = "application/octet-stream";
    std::string body;
};

std::string content_type(const fs::path& file) {
    static const std::map<std::string, std::string> types = {
        {".html", "text/html; charset=utf-8"}, {".js", "text/javascript; charset=utf-8"},
        {".json", "application/json"},         {".png", "image/png"},
        {".css", "text/css"}};
    const auto it = types.find(file.extension().string());
    return it == types.end() ? "application/octet-stream" : it->second;
}

Response file_response(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (file.empty() || !fs::is_regular_file(file) || !in) return {404, "text/plain", "not found\n"};
    std::ostringstream body;
    body << in.rdbuf();
    return {200, content_type(file), body.str()};
}

std::string percent_decoded(const std::string& s) {
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
            out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += s[i];
        }
    }
    return out;
}

Response range_image(const fs::path& run_dir, const std::string& frame) {
    if (frame.empty() || frame.size() > 9 || frame.find_first_not_of("0123456789") != std::string::npos)
        return {400, "text/plain", "bad frame number\n"};
    const fs::path exr = run_dir / "frames" / (frame_file_stem(std::stoull(frame)) + ".exr");
    if (!fs::is_regular_file(exr)) return {404, "text/plain", "no such frame\n"};
    const RangeImage image = read_frame_exr(exr);
    Response r{200, "application/octet-stream", {}};
    const std::uint32_t size[2] = {static_cast<std::uint32_t>(image.columns), static_cast<std::uint32_t>(image.rows)};
    r.body.append(reinterpret_cast<const char*>(size), sizeof size);
    r.body.append(reinterpret_cast<const char*>(image.range_m.data()), image.range_m.size() * sizeof(float));
    return r;
}

Response route(const ViewerOptions& o, const std::string& target) {
    const std::string path = percent_decoded(target.substr(0, target.find('?')));
    if (path == "/" || path == "/index.html") return file_response(o.viewer_dir / "index.html");
    if (path.rfind("/viewer/", 0) == 0) return file_response(resolve_inside(o.viewer_dir, path.substr(8)));
    if (path.rfind("/three/", 0) == 0) return file_response(resolve_inside(o.viewer_dir / "node_modules" / "three", path.substr(7)));
    if (path.rfind("/run/", 0) == 0) return file_response(resolve_inside(o.run_dir, path.substr(5)));
    if (path.rfind("/range/", 0) == 0) return range_image(o.run_dir, path.substr(7));
    if (path == "/files") {
        nlohmann::json names = nlohmann::json::array();
        for (const auto& entry : fs::directory_iterator(o.run_dir))
            if (entry.is_regular_file()) names.push_back(entry.path().filename().string());
        return {200, "application/json", names.dump()};
    }
    return {404, "text/plain", "not found\n"};
}

void answer(int client, const ViewerOptions& o) {
    std::string request;
    char buffer[4096];
    // The request line and headers; a GET has no body.
    while (request.find("\r\n\r\n") == std::string::npos && request.size() < 65536) {
        pollfd p{client, POLLIN, 0};
        if (poll(&p, 1, 2000) <= 0) return;
        const ssize_t n = recv(client, buffer, sizeof buffer, 0);
        if (n <= 0) return;
        request.append(buffer, static_cast<std::size_t>(n));
    }
    std::istringstream line(request.substr(0, request.find("\r\n")));
    std::string method, target;
    line >> method >> target;
    Response r = method == "GET" ? route(o, target) : Response{405, "text/plain", "only GET\n"};
    if (r.status == 404 && r.body.empty()) r.body = "not found\n";
    std::string head = "HTTP/1.1 " + std::to_string(r.status) + (r.status == 200 ? " OK" : " Error") +
                       "\r\nContent-Type: " + r.type + "\r\nContent-Length: " + std::to_string(r.body.size()) +
                       "\r\nCache-Control: no-store\r\nConnection: close\r\n\r\n";
    head += r.body;
    for (std::size_t sent = 0; sent < head.size();) {
        const ssize_t n = send(client, head.data() + sent, head.size() - sent, MSG_NOSIGNAL);
        if (n <= 0) return;
        sent += static_cast<std::size_t>(n);
    }
}

}  // namespace

fs::path resolve_inside(const fs::path& root, const std::string& request_path) {
    if (request_path.empty() || request_path.front() == '/') return {};
    const fs::path relative = fs::path(request_path).lexically_normal();
    for (const auto& part : relative) {
        const std::string s = part.string();
        if (s == ".." || (!s.empty() && s.front() == '.')) return {};
    }
    std::error_code ec;
    const fs::path base = fs::weakly_canonical(root, ec);
    const fs::path file = fs::weakly_canonical(base / relative, ec);
    if (ec) return {};
    // After symbolic links are followed the file must still lie under the root.
    const auto [end, ignored] = std::mismatch(base.begin(), base.end(), file.begin(), file.end());
    return end == base.end() ? file : fs::path{};
}

void serve_viewer(const ViewerOptions& o, const std::function<void(const std::string&)>& ready, const std::atomic<bool>& stop) {
    if (!fs::is_regular_file(o.run_dir / "manifest.json"))
        throw InputError(o.run_dir.string(), "DIR", "not a ladarsim run: no manifest.json");
    if (!fs::is_regular_file(o.viewer_dir / "node_modules" / "three" / "build" / "three.module.js"))
        throw InputError((o.viewer_dir / "node_modules").string(), "three", "three.js is missing: scripts/setup.sh installs it, then build (and install) again");
    const int server = socket(AF_INET, SOCK_STREAM, 0);
    if (server < 0) throw std::runtime_error("cannot open a socket");
    const int yes = 1;
    setsockopt(server, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);  // this machine only
    address.sin_port = htons(static_cast<std::uint16_t>(o.port));
    if (bind(server, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 || listen(server, 16) != 0) {
        close(server);
        throw InputError("--port", std::to_string(o.port), std::string("cannot listen on 127.0.0.1: ") + std::strerror(errno));
    }
    socklen_t length = sizeof address;
    getsockname(server, reinterpret_cast<sockaddr*>(&address), &length);
    ready("http://127.0.0.1:" + std::to_string(ntohs(address.sin_port)) + "/");
    while (!stop.load()) {
        pollfd p{server, POLLIN, 0};
        if (poll(&p, 1, 200) <= 0) continue;
        const int client = accept(server, nullptr, nullptr);
        if (client < 0) continue;
        try {
            answer(client, o);
        } catch (const std::exception&) {
            // A bad request or an unreadable file ends that connection, never the server.
        }
        close(client);
    }
    close(server);
}

}  // namespace ladarsim::apps
