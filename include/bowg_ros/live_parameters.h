// Live tuning through the parameter table: dynamic_reconfigure's values are
// applied to the options, and the values in force written back, by name for
// every parameter the message carries. No parameter is listed by hand, so a
// parameter added to cfg/BoWG.cfg (and to the table, which
// test/cfg_matches_table_test.cpp demands) is wired without further code.
#pragma once

#include <dynamic_reconfigure/Config.h>

#include "bowg/parameters/parameter_table.h"

namespace bowg_ros {

/// Sets every bool, int and double of `config` through bowg::setParameter
/// (booleans as 0/1). Throws bowg::InvalidParameter for a name the table does
/// not know, a value outside its range, or a string parameter (the table's
/// live parameters are numeric). Cross-field rules are not checked here
/// (bowg::correctLiveParameters, then validate()).
void applyLiveConfig(const dynamic_reconfigure::Config& config, bowg::PipelineOptions* options);

/// Overwrites the value of every bool, int and double of `config` with the
/// value `options` holds (bowg::getParameter), so that the client sees the
/// values in force after corrections or a rejection.
void writeLiveConfig(const bowg::PipelineOptions& options, dynamic_reconfigure::Config* config);

}  // namespace bowg_ros
