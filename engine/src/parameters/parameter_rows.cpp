// The table's rows, built once (parameter_rows.h).
#include "parameters/parameter_rows.h"

#include "bowg/core/errors.h"

namespace bowg {
namespace parameter_rows {

const std::vector<Row>& rows() {
  static const std::vector<Row> table = [] {
    std::vector<Row> r;
    addScoringRows(&r);
    addDetectionRows(&r);
    addFeatureRows(&r);
    return r;
  }();
  return table;
}

const Row& rowOf(const std::string& name) {
  for (const Row& r : rows()) {
    if (r.info.name == name) return r;
  }
  throw InvalidParameter("unknown parameter '" + name +
                         "' (see the parameter table in the README for the valid names)");
}

}  // namespace parameter_rows
}  // namespace bowg
