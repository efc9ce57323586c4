// bowg_merge_databases: one database of several missions (the surveys of one
// network) from saved detector files, to load as a reference map or to
// continue (bowg/detection/detector_merge.h).
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "bowg/core/atomic_file.h"
#include "bowg/database/database.h"
#include "bowg/detection/detector_merge.h"
#include "bowg/detection/loop_detector.h"
#include "bowg/vocabulary/vocabulary.h"
#include "bowg/vocabulary/vocabulary_io.h"

namespace {

const char* kUsage =
    "usage: bowg_merge_databases A B [C ...] -o OUT --vocabulary FILE\n"
    "\n"
    "Writes OUT (atomically) holding every mission of the database files A, B, ...\n"
    "(saved by the nodelet's ~database_save_path or save_database service) in the\n"
    "order of their first keyframe. Mission ids and names stay as they are and must\n"
    "differ between the files; every file must have been built with FILE, the\n"
    "vocabulary the missions were recorded with. A merged file merges again.\n";

struct Args {
  std::vector<std::string> inputs;
  std::string output, vocabulary;
};

// Exits 2 with the usage on a bad command line.
Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      std::exit(0);
    }
    if (arg == "-o" || arg == "--vocabulary") {
      if (i + 1 >= argc) {
        std::cerr << "error: " << arg << " needs a value\n" << kUsage;
        std::exit(2);
      }
      (arg == "-o" ? a.output : a.vocabulary) = argv[++i];
    } else if (!arg.empty() && arg[0] == '-') {
      std::cerr << "error: unknown option '" << arg << "'\n" << kUsage;
      std::exit(2);
    } else {
      a.inputs.push_back(arg);
    }
  }
  if (a.inputs.size() < 2 || a.output.empty() || a.vocabulary.empty()) {
    std::cerr << "error: need two database files or more, -o OUT and --vocabulary FILE\n" << kUsage;
    std::exit(2);
  }
  return a;
}

}  // namespace

int main(int argc, char** argv) {
  const Args args = parse(argc, argv);
  try {
    const auto vocabulary =
        std::make_shared<const bowg::Vocabulary>(bowg::loadVocabulary(args.vocabulary));
    bowg::writeFileAtomically(args.output, bowg::mergeDetectorFiles(args.inputs, vocabulary));
    // Read back as a detector would: the file written is the file checked.
    bowg::LoopDetector check(vocabulary, bowg::LoopDetectorOptions());
    check.load(args.output);
    std::cout << args.output << ": " << check.database().size() << " keyframes, "
              << check.database().missions().size() << " missions\n";
    for (const bowg::Mission& m : check.database().missions().all()) {
      std::cout << "  mission " << m.id << " '" << m.name << "': " << m.entries << " keyframes\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
