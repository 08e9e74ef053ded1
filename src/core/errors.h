// The error every layer throws for a setting out of its valid range. Each boundary turns it into
// its own error naming the key as its user spells it: a scene file's JSON path (SceneError), a
// command-line flag (the CLI's UsageError), a Python keyword (the module's ValueError).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace oceanref {

// A setting out of its valid range. `key` names the setting (snake_case, as in scene files);
// the message states the accepted range and the value given.
class SettingError : public std::invalid_argument {
 public:
  SettingError(std::string key, const std::string& message)
      : std::invalid_argument(message), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

}  // namespace oceanref
