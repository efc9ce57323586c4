// The one table of every user-facing BoWG parameter: its name (as written in
// config/*.yaml, in the nodelet's private parameters, in cfg/BoWG.cfg and in
// the offline evaluation tool), type, default, range, description and the
// options field it sets. Everything that turns names into options goes through
// here, so a misspelled key fails loudly (InvalidParameter) in every front end
// instead of being ignored in one of them (cartographer's lesson, see
// docs/style-examples.md).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "bowg/detection/detection_options.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/features/feature_extractor.h"

namespace bowg {

/// Everything a user configures: the detector (per keyframe) and the feature
/// extractor (per image).
struct PipelineOptions {
  LoopDetectorOptions detector;
  FeatureOptions features;

  /// Runs both validate()s; throws InvalidParameter naming the field.
  void validate() const;
};

enum class ParameterType { kBool, kInt, kDouble, kString, kEnum };
const char* toString(ParameterType t);

/// One row of the table.
struct ParameterInfo {
  std::string name;  ///< flat key, e.g. "lambda_1"
  ParameterType type;
  std::string group;  ///< "detector" or "features" (README table order)
  std::string field;  ///< the options field it sets, e.g. "similarity.lambda_1"
  double min_value;   ///< inclusive range for kInt/kDouble (ignored otherwise)
  double max_value;
  std::vector<std::string> choices;  ///< kEnum only
  /// True when cfg/BoWG.cfg exposes it (tunable while running).
  bool live;
  std::string description;
};

/// Every parameter, in a stable order (detector first, then features).
const std::vector<ParameterInfo>& parameterTable();

/// The row for `name`, or nullptr when there is none.
const ParameterInfo* findParameter(const std::string& name);

/// Sets one parameter from text ("0.4", "true", "gftt", ...). Throws
/// InvalidParameter naming the parameter for an unknown name, a value that
/// does not parse as the parameter's type, or a value outside its range.
/// Cross-field rules (lambda_1 + lambda_2 <= 1, ...) are checked by
/// PipelineOptions::validate(), not here, so parameters may be set in any
/// order.
void setParameter(const std::string& name, const std::string& value, PipelineOptions* options);

/// Sets a numeric or boolean parameter (booleans: 0 = false, 1 = true).
/// Throws InvalidParameter as above, also for string/enum parameters and for
/// non-integral values of integer parameters.
void setParameter(const std::string& name, double value, PipelineOptions* options);

/// The current value as text, in the form setParameter() parses.
std::string getParameter(const std::string& name, const PipelineOptions& options);

/// The default of `name` as text (the value in a default PipelineOptions).
std::string defaultValue(const std::string& name);

/// Applies every key/value (in key order), then validates the result. The
/// message of the first error names the parameter and, when given, `source`
/// (e.g. the yaml path).
void applyParameters(const std::map<std::string, std::string>& values, PipelineOptions* options,
                     const std::string& source = std::string());

/// Reads the flat yaml subset used by config/*.yaml: one `key: value` per
/// line, `#` comments, blank lines, optional single or double quotes around
/// values. Nested maps, lists and duplicate keys throw FormatError naming
/// the path and line; a missing file throws IoError.
std::map<std::string, std::string> readFlatYaml(const std::string& path);

/// readFlatYaml() + applyParameters() on top of `base`.
PipelineOptions loadParameterFile(const std::string& path,
                                  const PipelineOptions& base = PipelineOptions());

/// Corrects the live parameters a running detector receives (dynamic
/// reconfigure) instead of rejecting them: lambda_1 + lambda_2 > 1 ->
/// lambda_2 = 1 - lambda_1 (eq. 9 needs a non-negative distribution weight);
/// direct_index_level > vocabulary depth -> depth (the direct index needs an
/// existing level; `vocabulary_depth` <= 0 skips this rule); values outside
/// the table's range -> clamped. Returns one human-readable line per
/// correction (empty when nothing changed).
std::vector<std::string> correctLiveParameters(int vocabulary_depth, PipelineOptions* options);

}  // namespace bowg
