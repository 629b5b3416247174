// libFuzzer target: any bytes as a browser's WebSocket message to the IDE
// server. parse_request may only answer with a request or RequestError.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "tools/ide/requests.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    std::string_view text(reinterpret_cast<const char *>(data), size);
    try {
        aseba::ide::parse_request(text);
    } catch (const aseba::ide::RequestError &) {
    } catch (...) {
        std::abort(); // anything else would escape the server's handler
    }
    aseba::ide::request_id_of(text);
    return 0;
}
