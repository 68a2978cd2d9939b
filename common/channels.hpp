// The chain's channel names (README "Channels"), as every program defaults them.
#pragma once

#include <string>

namespace stairs {

struct ChainChannels {
  std::string depth = "STAIRS_DEPTH";
  std::string observation = "STAIRS_OBSERVATION";
  std::string model = "STAIRS_MODEL";
  std::string truth = "STAIRS_GROUND_TRUTH";
};

}  // namespace stairs
