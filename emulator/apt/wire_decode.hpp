#pragma once
// The wire log's reading of an APT frame (docs/control-api/apt.md "Wire log"): the manual's
// name, source, destination and the fields of the codec's struct by name. Runs only when
// someone reads the log or listens to its events.

#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <string_view>
#include <vector>

namespace rigsim::apt {

/// One recorded frame as {"id": "0x0453", "name", "source": "0x01", "destination": "0x50",
/// "fields": {...}}; bytes that are no whole frame as {"name": "not a frame"}.
void decode_for_log(std::string_view frame, nlohmann::json& out);

/// The field names of message `id` in wire order (the codec struct's members), or nullptr
/// (a header-only message whose only field is its channel, or a status structure).
const std::vector<std::string_view>* field_names(std::uint16_t id);

/// The manual's names of the status bits set in `bits` ("homed", "enabled", ...), lowest first.
std::vector<std::string_view> status_bit_names(std::uint32_t bits);

} // namespace rigsim::apt
