// EnumTable: the one {value, name} table of an enum, with generic name and parse. Every enum of
// the library that has a textual form (in JSON, in traces, on the command line) is listed once,
// as a table, and read through these functions.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace clothref {

template <typename E>
struct EnumName {
  E value;
  std::string_view name;
};

template <typename E, std::size_t N>
using EnumTable = std::array<EnumName<E>, N>;

// The name of `value` in `table`, or "?" for a value the table does not list.
template <typename E, std::size_t N>
constexpr std::string_view enumName(const EnumTable<E, N>& table, E value) {
  for (const EnumName<E>& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

// The value named `name`, or nothing.
template <typename E, std::size_t N>
constexpr std::optional<E> parseEnum(const EnumTable<E, N>& table, std::string_view name) {
  for (const EnumName<E>& entry : table)
    if (entry.name == name) return entry.value;
  return std::nullopt;
}

// "a, b, c": the names in table order, for messages.
template <typename E, std::size_t N>
std::string enumNames(const EnumTable<E, N>& table) {
  std::string names;
  for (const EnumName<E>& entry : table) {
    if (!names.empty()) names += ", ";
    names += entry.name;
  }
  return names;
}

}  // namespace clothref
