// A small streaming JSON writer (the toolkit writes JSON reports; it never needs to read them).
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace tsrir {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out, bool pretty = true);
  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(const std::string& k);
  JsonWriter& value(const std::string& v);
  JsonWriter& value(const char* v);
  JsonWriter& value(double v);  // NaN/Inf are written as null
  JsonWriter& value(int v);
  JsonWriter& value(long v);
  JsonWriter& value(long long v);
  JsonWriter& value(size_t v);
  JsonWriter& value(bool v);
  JsonWriter& null();
  template <typename T>
  JsonWriter& field(const std::string& k, const T& v) { key(k); return value(v); }

 private:
  void before_value();
  void newline();
  std::ostream& out_;
  bool pretty_;
  std::vector<bool> first_;  // per open container: no element written yet
  bool after_key_ = false;
};

std::string json_escape(const std::string& s);

}  // namespace tsrir
