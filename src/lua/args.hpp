// A function's table of named arguments, checked against the function's keys (arg_spec.hpp).
// Everything here reads the table raw (lua_rawget, lua_rawlen, lua_next): a metatable on an argument
// table cannot run code (and raise a Lua error) while C++ objects are alive, and no function here
// raises a Lua error: a bad argument throws Error, which `guarded` turns into a Lua error once the C++
// frame is gone. Messages name the key and the allowed range.
#pragma once

#include <lua.hpp>

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "arg_spec.hpp"
#include "core/types.hpp"

namespace seismpm::lua {

class Args {
 public:
  // Checks the table at `index`: first any key that `keys` does not have (entries 1..n only when it
  // has a Positional key), so a misspelt key is named before a missing one; then each key in order:
  // missing, wrong type, out of range (nested tables too). `within` names the key of a nested table.
  Args(lua_State* L, int index, std::span<const Key> keys, const char* within = nullptr);

  bool has(const char* key) const;
  // Pushes the value of `key` (nil if absent) and returns its Lua type.
  int push(const char* key) const;

  // The value, or the key's default when absent; "missing key" when it has none.
  double number(const char* key) const;
  // A default that depends on other arguments (a residual strength defaults to the peak one).
  double number(const char* key, double fallback) const;
  std::optional<double> optional_number(const char* key) const;
  int integer(const char* key) const;
  int integer(const char* key, int fallback) const;
  std::string string(const char* key) const;
  std::string string(const char* key, const std::string& fallback) const;
  std::string choice(const char* key) const;
  std::string choice(const char* key, const std::string& fallback) const;
  std::string choice(const char* key, const std::vector<std::string>& allowed, const std::string& fallback) const;
  bool boolean(const char* key) const;
  bool boolean(const char* key, bool fallback) const;
  Vec<2> point(const char* key) const;  // {x, y}
  // A non-empty list of strings {"a", "b"}; the key's default when absent, nullopt when it has none.
  std::optional<std::vector<std::string>> names(const char* key) const;
  // The nested table of a Table key, checked; it stays on the stack until the function returns.
  Args table(const char* key) const;

  // Number of positional entries (the table's raw length).
  lua_Integer length() const;
  // Reads positional entry i: a number, or a point {x, y}.
  double number_at(lua_Integer i) const;
  Vec<2> point_at(lua_Integer i, const std::string& what) const;

  lua_State* state() const { return L_; }
  int index() const { return index_; }

 private:
  const Key& spec(const char* key) const;  // throws std::logic_error for a key the description lacks
  void reject_unknown_keys(const std::vector<std::string>& known, bool positional) const;
  void check(const Key& k) const;
  std::string context() const;  // "key 'softening': " inside a nested table

  lua_State* L_;
  int index_;
  std::span<const Key> keys_;
  const char* within_ = nullptr;
};

// Reads {x, y} at `index` (raw); `what` names it in messages.
Vec<2> to_point(lua_State* L, int index, const std::string& what);

}  // namespace seismpm::lua
