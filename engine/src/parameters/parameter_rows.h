// The rows of the parameter table (parameter_table.h): each ties a name,
// type, range and description to one PipelineOptions field. Internal to the
// parameters stage; the rows are written per stage in
// parameter_rows_{scoring,detection,features}.cpp.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bowg/parameters/parameter_table.h"

namespace bowg {
namespace parameter_rows {

/// A row plus the accessors that tie it to a PipelineOptions field. Exactly
/// one accessor matching info.type is set.
struct Row {
  ParameterInfo info;
  std::function<bool*(PipelineOptions*)> as_bool;
  std::function<int*(PipelineOptions*)> as_int;
  std::function<double*(PipelineOptions*)> as_double;
  std::function<std::string*(PipelineOptions*)> as_string;
  std::function<void(PipelineOptions*, const std::string&)> set_enum;
  std::function<std::string(const PipelineOptions&)> get_enum;
};

inline Row boolRow(const std::string& name, const std::string& group, const std::string& field,
                   bool live, std::function<bool*(PipelineOptions*)> f, const std::string& d) {
  Row r;
  r.info = ParameterInfo{name, ParameterType::kBool, group, field, 0, 1, {}, live, d};
  r.as_bool = std::move(f);
  return r;
}

inline Row intRow(const std::string& name, const std::string& group, const std::string& field,
                  int lo, int hi, bool live, std::function<int*(PipelineOptions*)> f,
                  const std::string& d) {
  Row r;
  r.info =
      ParameterInfo{name, ParameterType::kInt, group, field, double(lo), double(hi), {}, live, d};
  r.as_int = std::move(f);
  return r;
}

inline Row doubleRow(const std::string& name, const std::string& group, const std::string& field,
                     double lo, double hi, bool live, std::function<double*(PipelineOptions*)> f,
                     const std::string& d) {
  Row r;
  r.info = ParameterInfo{name, ParameterType::kDouble, group, field, lo, hi, {}, live, d};
  r.as_double = std::move(f);
  return r;
}

inline Row stringRow(const std::string& name, const std::string& group, const std::string& field,
                     std::function<std::string*(PipelineOptions*)> f, const std::string& d) {
  Row r;
  r.info = ParameterInfo{name, ParameterType::kString, group, field, 0, 0, {}, false, d};
  r.as_string = std::move(f);
  return r;
}

inline Row enumRow(const std::string& name, const std::string& group, const std::string& field,
                   std::vector<std::string> choices,
                   std::function<void(PipelineOptions*, const std::string&)> set,
                   std::function<std::string(const PipelineOptions&)> get, const std::string& d) {
  Row r;
  r.info =
      ParameterInfo{name, ParameterType::kEnum, group, field, 0, 0, std::move(choices), false, d};
  r.set_enum = std::move(set);
  r.get_enum = std::move(get);
  return r;
}

/// The accessor of one PipelineOptions field, e.g.
/// BOWG_FIELD(double, detector.similarity.lambda_1).
#define BOWG_FIELD(type, expr) [](PipelineOptions* o) -> type* { return &o->expr; }

/// The rows of each stage, in table order (detector first, then features).
void addScoringRows(std::vector<Row>* rows);
void addDetectionRows(std::vector<Row>* rows);
void addFeatureRows(std::vector<Row>* rows);

/// Every row, built once.
const std::vector<Row>& rows();

/// The row of `name`; throws InvalidParameter for an unknown name.
const Row& rowOf(const std::string& name);

}  // namespace parameter_rows
}  // namespace bowg
