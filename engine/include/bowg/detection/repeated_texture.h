// The pipe's repeated texture, as the robot's own recent past shows it: a
// feature of the query that finds a correspondence in keyframes driven a
// little before it (farther back than the query's own wall reaches, closer
// than any loop candidate) belongs to what every section repeats, the
// shared grain and the joints. The rest (unique marks, the wall's own
// grain, new structure) is what a loop's inliers must include to tell the
// place from its look-alikes (VerifiedChainOptions::min_unique_inliers).
#pragma once

#include <vector>

#include "bowg/core/types.h"
#include "bowg/database/database.h"
#include "bowg/detection/detection_options.h"
#include "bowg/detection/geometric_verification.h"

namespace bowg {

/// The keyframes that stand for the query's recent past: `chain.
/// repeated_texture_keyframes` of them, the newest entries driven at least
/// repeated_texture_min_m + j * (recent_exclusion_m - repeated_texture_min_m)
/// / (n - 1) back for j = 0..n-1 when the query has an odometer, else the
/// entries recent_exclusion * j / n keyframes back for j = 1..n; each once,
/// entries without an odometer left out in the first case.
std::vector<EntryId> repeatedTextureEntries(const Database& database, double query_odometer,
                                            const VerifiedChainOptions& chain,
                                            const IslandOptions& islands);

/// Marks in `repeated` (one flag per query feature) the query features that
/// have a correspondence (findCorrespondences) with `entry`.
void markRepeated(const VerificationView& query, const VerificationView& entry,
                  const GeometricVerificationOptions& options, std::vector<char>* repeated);

/// The inliers whose query feature is not marked repeated.
int uniqueInliers(const std::vector<Correspondence>& inliers, const std::vector<char>& repeated);

}  // namespace bowg
