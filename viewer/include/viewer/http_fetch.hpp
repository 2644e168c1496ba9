// viewer/http_fetch.hpp — downloads for the streaming viewer through libcurl: HTTP(S) GET of a
// manifest or an HNI, as a Fetch for the loader threads (viewer/city_loader.hpp).
#pragma once

#include <string>

#include <viewer/city_loader.hpp>

namespace nut::viewer {

// Whether a location is a URL the HTTP fetch serves (http:// or https://).
bool isUrl(const std::string& location);

// GET through libcurl, one easy handle per call (thread-safe: libcurl is initialised once, before
// the first call). Errors name the URL: the transport's ("connection refused", "timeout"), an
// HTTP status of 400 or more ("HTTP 404"), or a body over 256 MiB. Redirects are followed; a
// connection waits at most 10 s, and a transfer slower than 1 KB/s for 30 s is abandoned.
Fetch httpFetch();

// Local files for a path, HTTP for a URL.
Fetch fetchFor(const std::string& location);

}  // namespace nut::viewer
