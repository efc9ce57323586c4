// bowg_train_vocabulary's progress bar on stderr, shared by the feature
// extraction (the first 20 %) and the training (the rest).
#pragma once

#include <string>

namespace bowg {
namespace train_vocabulary_app {

/// Draws `fraction` (0..1) and the name of the current stage.
void progressBar(double fraction, const std::string& stage);

}  // namespace train_vocabulary_app
}  // namespace bowg
