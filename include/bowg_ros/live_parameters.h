// Live tuning through the parameter table: dynamic_reconfigure's values are
// applied to the options, and the values in force written back, by name for
// every parameter the message carries. No parameter is listed by hand, so a
// parameter added to cfg/BoWG.cfg (and to the table, which
// test/cfg_matches_table_test.cpp demands) is wired without further code.
#pragma once

#include <dynamic_reconfigure/Config.h>
#include <dynamic_reconfigure/ConfigDescription.h>

#include <string>
#include <vector>

#include "bowg/parameters/parameter_table.h"

namespace bowg_ros {

/// Sets every live bool, int and double of `config` through
/// bowg::setParameter (booleans as 0/1); start-only parameters are skipped
/// (startOnlyRequests() reports them). Throws bowg::InvalidParameter for a
/// name the table does not know, a value outside its range ("min_score: 99
/// is outside [0, 10]"), or a live string. Cross-field rules are not checked
/// here (bowg::correctLiveParameters, then validate()).
void applyLiveConfig(const dynamic_reconfigure::Config& config, bowg::PipelineOptions* options);

/// The live parameters' values in force, as cfg/BoWG.cfg's message (what
/// the server sends back and publishes).
dynamic_reconfigure::Config liveConfig(const bowg::PipelineOptions& options);

/// cfg/BoWG.cfg's description plus a group "start_only" listing every other
/// parameter of the table with its value in force as default, minimum and
/// maximum. A client (dynparam, rqt_reconfigure) refuses names it was not
/// told about with "don't know parameter"; told about them, it sends them,
/// and the nodelet answers that they are read at start-up only. The values
/// sent back (liveConfig) carry the live parameters only, so typed clients
/// (dynamic_reconfigure::Client<BoWGConfig>) read them unchanged.
dynamic_reconfigure::ConfigDescription describeWithStartOnly(const bowg::PipelineOptions& options);

/// One message per start-only parameter that `requested` sets to a value
/// other than the one in force: "<name> is start-only ...".
std::vector<std::string> startOnlyRequests(const dynamic_reconfigure::Config& requested,
                                           const bowg::PipelineOptions& options);

/// Overwrites the value of every bool, int and double of `config` with the
/// value `options` holds (bowg::getParameter), so that the client sees the
/// values in force after corrections or a rejection.
void writeLiveConfig(const bowg::PipelineOptions& options, dynamic_reconfigure::Config* config);

}  // namespace bowg_ros
