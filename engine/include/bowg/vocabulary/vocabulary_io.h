// Vocabulary files: our own binary format and the formats users already own
// (DBoW2 / DBoW3 YAML, DBoW3 binary, ORB-SLAM text, VINS binary). Loaders
// detect the format, validate everything before trusting a count, and throw
// IoError (cannot read/write) or FormatError (corrupt, truncated, wrong
// format) with the path and what is wrong; writers are atomic.
//
// Descriptor bit order (see types.h: bit b = bit b%64 of block b/64):
//  - ORB (DBoW2 FORB, DBoW3, ORB-SLAM): byte j of the OpenCV descriptor is
//    bits 8j..8j+7, byte value bit t = descriptor bit 8j+t.
//  - BRIEF (DBoW2 FBrief, VINS): a boost::dynamic_bitset<> of 256 bits.
//    Its bit b is our bit b. In VINS' binary file block 0 of the bitset holds
//    bits 0..63 (dynamic_bitset's block order), so the four uint64 blocks map
//    1:1 onto Descriptor::bits. In DBoW2's YAML the bitset is written with
//    boost::to_string, most significant bit first: character i of the
//    256-character string is bit 255 - i.
#pragma once

#include <string>

#include "bowg/vocabulary/vocabulary.h"

namespace bowg {

enum class VocabularyFormat {
  kBowg,            ///< ".bowgvoc": ours (see vocabulary_io_bowg.cpp)
  kDbow2Yaml,       ///< DBoW2 OpenCV YAML (.yml / .yml.gz), ORB descriptors
  kDbow2BriefYaml,  ///< DBoW2 OpenCV YAML with BRIEF bit-string descriptors
  kDbow3Yaml,       ///< DBoW3 OpenCV YAML ("dbw3 <type> <cols> ..." descriptors)
  kDbow3Binary,     ///< DBoW3 binary (uncompressed; QuickLZ-compressed files are refused)
  kOrbSlamText,     ///< ORB-SLAM's ORBvoc.txt
  kVinsBinary,      ///< VINS-Mono / VINS-Fusion brief_k10L6.bin
};

/// "bowg", "dbow2_yaml", "dbow2_brief_yaml", "dbow3_yaml", "dbow3",
/// "orbslam_txt", "vins_bin". Parsing throws std::invalid_argument naming the
/// value and the accepted names.
VocabularyFormat vocabularyFormatFromString(const std::string& s);
std::string toString(VocabularyFormat f);

/// Detects the format from the file's content (magic numbers, YAML header,
/// text header), falling back on the extension only for VINS' magic-less
/// binary. Throws IoError if unreadable, FormatError if unrecognised.
VocabularyFormat detectVocabularyFormat(const std::string& path);

/// Loads any supported format (detected as above).
Vocabulary loadVocabulary(const std::string& path);
/// Loads a file of a known format (no detection).
Vocabulary loadVocabulary(const std::string& path, VocabularyFormat format);

/// Writes atomically. Foreign formats store what they can: node ids are our
/// node indices (children consecutive), so a round trip through any format
/// gives back the same fingerprint. Exceptions: ORB-SLAM text numbers words
/// in leaf order by construction, and its text weights are printed with 17
/// significant digits (exact). Throws IoError on failure.
void saveVocabulary(const Vocabulary& vocabulary, const std::string& path,
                    VocabularyFormat format = VocabularyFormat::kBowg);

}  // namespace bowg
