// Time histories (a velocity record, a load factor): piecewise-linear tables, constants, or a
// function supplied by a front end. Zero before a table starts and after it ends (a record stops).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace seismpm {

class History {
 public:
  virtual ~History() = default;
  virtual double at(double t) const = 0;
  virtual std::string describe() const = 0;
};

class ConstantHistory : public History {
 public:
  explicit ConstantHistory(double value) : value_(value) {}
  double at(double) const override { return value_; }
  double value() const { return value_; }
  std::string describe() const override;

 private:
  double value_;
};

class TableHistory : public History {
 public:
  // Throws InputError for an empty table, non-finite values or times that do not increase.
  // `source` names where the table came from, for messages ("table", "data/vx.csv").
  TableHistory(std::vector<double> times, std::vector<double> values, std::string source = "table");
  double at(double t) const override;
  std::string describe() const override;
  const std::vector<double>& times() const { return t_; }
  const std::vector<double>& values() const { return v_; }
  // Where the table came from ("table", a file name), without its point count.
  const std::string& source() const { return source_; }
  double start() const { return t_.front(); }
  double end() const { return t_.back(); }

 private:
  std::vector<double> t_, v_;
  std::string source_;
};

class FunctionHistory : public History {
 public:
  FunctionHistory(std::function<double(double)> f, std::string description)
      : f_(std::move(f)), description_(std::move(description)) {}
  double at(double t) const override { return f_(t); }
  std::string describe() const override { return description_; }

 private:
  std::function<double(double)> f_;
  std::string description_;
};

}  // namespace seismpm
