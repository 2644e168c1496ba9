// Downloads through libcurl (viewer/http_fetch.hpp).
#include <viewer/http_fetch.hpp>

#include <mutex>

#include <curl/curl.h>

namespace nut::viewer {

namespace {

constexpr std::size_t kMaxBodyBytes = std::size_t{256} << 20;

struct Body {
  std::vector<std::uint8_t> bytes;
  bool tooLarge = false;
};

std::size_t append(char* data, std::size_t size, std::size_t count, void* user) {
  auto* body = static_cast<Body*>(user);
  const std::size_t n = size * count;
  if (body->bytes.size() + n > kMaxBodyBytes) {
    body->tooLarge = true;
    return 0;  // aborts the transfer
  }
  body->bytes.insert(body->bytes.end(), data, data + n);
  return n;
}

}  // namespace

bool isUrl(const std::string& location) {
  return location.rfind("http://", 0) == 0 || location.rfind("https://", 0) == 0;
}

Fetch httpFetch() {
  // curl_global_init is not thread-safe: once, before any loader thread calls.
  static std::once_flag initialised;
  std::call_once(initialised, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
  return [](const std::string& url) -> Result<std::vector<std::uint8_t>> {
    CURL* curl = curl_easy_init();
    if (!curl) return Error{url + ": cannot start a download (curl_easy_init)"};
    Body body;
    char message[CURL_ERROR_SIZE] = {0};
    curl_easy_setopt(curl, CURLOPT_URL, url.c_str());
    curl_easy_setopt(curl, CURLOPT_WRITEFUNCTION, append);
    curl_easy_setopt(curl, CURLOPT_WRITEDATA, &body);
    curl_easy_setopt(curl, CURLOPT_ERRORBUFFER, message);
    curl_easy_setopt(curl, CURLOPT_FOLLOWLOCATION, 1L);
    curl_easy_setopt(curl, CURLOPT_MAXREDIRS, 5L);
    curl_easy_setopt(curl, CURLOPT_CONNECTTIMEOUT, 10L);
    curl_easy_setopt(curl, CURLOPT_LOW_SPEED_LIMIT, 1024L);
    curl_easy_setopt(curl, CURLOPT_LOW_SPEED_TIME, 30L);
    curl_easy_setopt(curl, CURLOPT_NOSIGNAL, 1L);  // loader threads: no SIGALRM for timeouts
    const CURLcode code = curl_easy_perform(curl);
    long status = 0;
    curl_easy_getinfo(curl, CURLINFO_RESPONSE_CODE, &status);
    curl_easy_cleanup(curl);
    if (body.tooLarge) return Error{url + ": larger than 256 MiB"};
    if (code != CURLE_OK) return Error{url + ": " + (message[0] ? message : curl_easy_strerror(code))};
    if (status >= 400) return Error{url + ": HTTP " + std::to_string(status)};
    return std::move(body.bytes);
  };
}

Fetch fetchFor(const std::string& location) { return isUrl(location) ? httpFetch() : localFiles(); }

}  // namespace nut::viewer
