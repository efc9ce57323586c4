// cfg/BoWG.cfg and the engine's parameter table must agree: same names,
// defaults (a default PipelineOptions), ranges and live flags, so the
// dynamic_reconfigure GUI, the yaml files and the README say one thing.
#include <dynamic_reconfigure/Config.h>
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "bowg/parameters/parameter_table.h"
#include "bowg_ros/BoWGConfig.h"

namespace bowg_ros {
namespace {

// Value of `name` in a config, as a double; false when absent.
bool valueOf(const BoWGConfig& config, const std::string& name, double* v) {
  dynamic_reconfigure::Config msg;
  config.__toMessage__(msg);
  for (const auto& p : msg.doubles) {
    if (p.name == name) return (*v = p.value), true;
  }
  for (const auto& p : msg.ints) {
    if (p.name == name) return (*v = p.value), true;
  }
  for (const auto& p : msg.bools) {
    if (p.name == name) return (*v = p.value ? 1.0 : 0.0), true;
  }
  return false;
}

TEST(CfgMatchesTable, EveryCfgParameterIsALiveTableRowWithTheSameDefaultAndRange) {
  std::set<std::string> in_cfg;
  for (const auto& d : BoWGConfig::__getParamDescriptions__()) {
    SCOPED_TRACE(d->name);
    in_cfg.insert(d->name);
    const bowg::ParameterInfo* p = bowg::findParameter(d->name);
    ASSERT_NE(p, nullptr) << "cfg parameter not in the table";
    EXPECT_TRUE(p->live);
    double def = 0, lo = 0, hi = 0;
    ASSERT_TRUE(valueOf(BoWGConfig::__getDefault__(), d->name, &def));
    ASSERT_TRUE(valueOf(BoWGConfig::__getMin__(), d->name, &lo));
    ASSERT_TRUE(valueOf(BoWGConfig::__getMax__(), d->name, &hi));
    const std::string table_default = bowg::defaultValue(d->name);
    if (p->type == bowg::ParameterType::kBool) {
      EXPECT_EQ(def, table_default == "true" ? 1.0 : 0.0);
    } else {
      EXPECT_EQ(def, std::stod(table_default));
      EXPECT_EQ(lo, p->min_value);
      EXPECT_EQ(hi, p->max_value);
    }
    EXPECT_FALSE(d->description.empty());
  }
  for (const bowg::ParameterInfo& p : bowg::parameterTable()) {
    if (p.live) EXPECT_TRUE(in_cfg.count(p.name)) << p.name << " is live but not in BoWG.cfg";
  }
}

}  // namespace
}  // namespace bowg_ros
