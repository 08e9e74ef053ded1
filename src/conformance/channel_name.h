// The EXR channel name of a field in the fields and stage files (docs/FILES.md): the one place
// that says how a field name ("c0.height", "c0.low.h0.re", "sum.normal_x") becomes the name of
// its channel in a file.
//
// Blender (3.4) reads a multi-part EXR as a multilayer image and splits every channel name at
// its dots from the right into layer.pass.channel: the last piece must be a channel id (one
// letter; a few two-letter and colour words), the piece before it is the pass, the rest the
// layer (source/blender/imbuf/intern/openexr/openexr_api.cpp; tools/blender_read_exr.py). A name
// ending in a longer piece ("height", "re", "normal_x") is dropped ("multilayer read: unknown
// channel token"). So every channel is the field name plus ".V", a one-channel pass that Blender
// offers as a Value: "c0.height.V", "c0.low.h0.re.V", "sum.normal_x.V" (measured with
// tools/blender_check.sh on Blender 3.4.1: every channel read bit-identically).
//
// The field names stay what the golden hashes (manifest fields_sha256, fields_f64_sha256) and
// the unit attributes (oceanref.units.<field name>) are defined over; only the channel names in
// the file carry the suffix.
#pragma once

#include <string>
#include <string_view>

namespace oceanref {

// The suffix Blender needs: a one-letter channel id (V, a value).
inline constexpr std::string_view kExrChannelSuffix = ".V";

// The channel name of field `field_name` in a fields or stage file.
inline std::string exr_channel_name(std::string_view field_name) {
  return std::string(field_name) + std::string(kExrChannelSuffix);
}

// The field name of a channel of a fields or stage file: the channel name without its ".V";
// a name without the suffix is returned unchanged (it is not a field channel).
inline std::string field_name_of_channel(std::string_view channel_name) {
  if (channel_name.size() > kExrChannelSuffix.size() && channel_name.ends_with(kExrChannelSuffix)) {
    channel_name.remove_suffix(kExrChannelSuffix.size());
  }
  return std::string(channel_name);
}

}  // namespace oceanref
