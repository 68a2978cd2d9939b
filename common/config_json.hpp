// Config structs <-> JSON through one field list per struct. Each config
// struct lists its fields once, with the allowed range:
//
//   template <class V> void visit(V& v) {
//     v("grid_cell_px", grid_cell_px, 1, 64);
//     v("smooth_normals", smooth_normals);
//     v.section("verification", verification);
//   }
//
// and that list reads a JSON object (ConfigReader: any subset of the keys; an
// unknown key, a wrong type or a value out of range is an error naming the
// file, the key's full path and the allowed range) and writes one
// (ConfigWriter: --print-config, the shipped config/default.json).
#pragma once

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace stairs {

// Keeps the range's type from taking part in deduction: v("x_m", x_m, 0, 1) on a float.
template <class T>
struct ConfigValue {
  using type = T;
};
template <class T>
using config_value_t = typename ConfigValue<T>::type;

class ConfigReader {
 public:
  // `file` names the source in errors; `path` is the object's key path ("perception.normals").
  ConfigReader(const nlohmann::json& object, std::string file, std::string path)
      : object_(object), file_(std::move(file)), path_(std::move(path)) {
    if (!object_.is_object()) fail(path_.empty() ? "must be a JSON object" : "'" + path_ + "' must be a JSON object");
  }

  template <class T>
  void operator()(const char* key, T& field, config_value_t<T> min, config_value_t<T> max) {
    static_assert(std::is_arithmetic_v<T> && !std::is_same_v<T, bool>);
    const nlohmann::json* v = take(key);
    if (!v) return;
    const bool type_ok = std::is_integral_v<T> ? v->is_number_integer() : v->is_number();
    if (!type_ok) fail("'" + full(key) + "' must be " + (std::is_integral_v<T> ? "an integer" : "a number"));
    const double x = v->get<double>();
    if (!(x >= static_cast<double>(min) && x <= static_cast<double>(max)))
      fail("'" + full(key) + "' = " + v->dump() + " is out of range: allowed " + range(min, max));
    field = v->get<T>();
  }
  void operator()(const char* key, bool& field) {
    const nlohmann::json* v = take(key);
    if (!v) return;
    if (!v->is_boolean()) fail("'" + full(key) + "' must be true or false");
    field = v->get<bool>();
  }
  template <class Sub>
  void section(const char* key, Sub& sub) {
    const nlohmann::json* v = take(key);
    if (!v) return;
    ConfigReader r(*v, file_, full(key));
    sub.visit(r);
    r.finish();
  }
  // Every key of the object must have been read: a typo is an error, not a default.
  void finish() const {
    for (const auto& [key, value] : object_.items()) {
      bool known = false;
      for (const std::string& k : seen_) known = known || k == key;
      if (!known) fail("unknown key '" + full(key) + "'" + hint_);
    }
  }
  // Appended to the unknown-key error (e.g. where the keys of an old flat file went).
  void set_unknown_key_hint(std::string hint) { hint_ = std::move(hint); }

 private:
  const nlohmann::json* take(const char* key) {
    seen_.emplace_back(key);
    const auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
  }
  std::string full(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  template <class T>
  static std::string range(T min, T max) {
    std::ostringstream s;
    s << min << ".." << max;
    return s.str();
  }
  [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(file_ + ": " + what); }

  const nlohmann::json& object_;
  std::string file_, path_, hint_;
  std::vector<std::string> seen_;
};

class ConfigWriter {
 public:
  template <class T>
  void operator()(const char* key, const T& field, config_value_t<T>, config_value_t<T>) {
    if constexpr (std::is_same_v<T, float>) {
      // The shortest decimal that reads back as this float: 0.1, not 0.10000000149.
      char buf[32];
      const auto end = std::to_chars(buf, buf + sizeof buf, field).ptr;
      out_[key] = std::stod(std::string(buf, end));
    } else {
      out_[key] = field;
    }
  }
  void operator()(const char* key, const bool& field) { out_[key] = field; }
  template <class Sub>
  void section(const char* key, const Sub& sub) {
    ConfigWriter w;
    const_cast<Sub&>(sub).visit(w);
    out_[key] = w.json();
  }
  const nlohmann::ordered_json& json() const { return out_; }

 private:
  nlohmann::ordered_json out_ = nlohmann::ordered_json::object();  // keys in the struct's order
};

// Checks values set in code (a command-line override, a test) against the
// same ranges; the error names the key's full path and the allowed range.
class ConfigChecker {
 public:
  explicit ConfigChecker(std::string path) : path_(std::move(path)) {}
  template <class T>
  void operator()(const char* key, const T& field, config_value_t<T> min, config_value_t<T> max) {
    if (!(field >= min && field <= max)) {
      std::ostringstream s;
      s << "'" << path_ << "." << key << "' = " << field << " is out of range: allowed " << min << ".." << max;
      throw std::runtime_error(s.str());
    }
  }
  void operator()(const char*, const bool&) {}
  template <class Sub>
  void section(const char* key, const Sub& sub) {
    ConfigChecker c(path_ + "." + key);
    const_cast<Sub&>(sub).visit(c);
  }

 private:
  std::string path_;
};

// Reads `object` (the config file's `path` object, e.g. "tracker") into a
// Config: every key checked, `hint` appended to an unknown-key error.
template <class Config>
Config read_config(const nlohmann::json& object, const std::string& file, const std::string& path,
                   const std::string& hint) {
  Config c;
  ConfigReader r(object, file, path);
  r.set_unknown_key_hint(hint);
  c.visit(r);
  r.finish();
  return c;
}

// The JSON of a config struct (all fields, effective values, in field order).
template <class Config>
nlohmann::ordered_json config_to_json(const Config& c) {
  ConfigWriter w;
  const_cast<Config&>(c).visit(w);
  return w.json();
}

}  // namespace stairs
