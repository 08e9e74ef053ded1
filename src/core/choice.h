// Named values of an enumeration: one table per enum, next to the enum, from which every
// boundary (scene files, the command line, the Python module) parses and prints its names, so a
// name is written once and every error lists the same valid values.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include "core/format.h"

namespace oceanref {

template <class E>
struct Choice {
  using Enum = E;
  E value;
  std::string_view name;
};

// The names of a table (a std::array or std::span of Choice): "a", "a or b", "one of a, b, c".
template <class Table>
std::string choice_names(const Table& table) {
  std::string out = table.size() > 2 ? "one of " : "";
  for (std::size_t i = 0; i < table.size(); ++i) {
    if (i > 0) out += table.size() == 2 ? " or " : ", ";
    out += table[i].name;
  }
  return out;
}

// The value named `name`, if the table has it.
template <class Table>
auto find_choice(const Table& table, std::string_view name)
    -> std::optional<typename Table::value_type::Enum> {
  for (const auto& c : table) {
    if (c.name == name) return c.value;
  }
  return std::nullopt;
}

// The name of `value` ("?" if the table does not hold it).
template <class Table>
std::string_view choice_name(const Table& table, typename Table::value_type::Enum value) {
  for (const auto& c : table) {
    if (c.value == value) return c.name;
  }
  return "?";
}

// The value named `text`, or throws Error(key, "expected a, b or c; got 'text'") (`text` escaped,
// core/format.h escape_value): Error is the
// caller's error type with a (key, message) constructor — SettingError, a scene's SceneError
// (key: the JSON path), the command line's UsageError (the flag), the Python module's
// ArgumentError (the keyword) — each of which shows the key before the message.
template <class Error, class Table>
auto parse_choice(const Table& table, const std::string& key, std::string_view text) ->
    typename Table::value_type::Enum {
  if (const auto v = find_choice(table, text)) return *v;
  throw Error(key, "expected " + choice_names(table) + "; got '" + escape_value(text) + "'");
}

}  // namespace oceanref
