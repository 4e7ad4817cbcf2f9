// The shapes a rock can take (paper 3.1; rockfall/rock.hpp builds each one). In core because a
// release feature may name the shape of its rocks (release_conditions.hpp).
#pragma once

namespace talus {

enum class BlockShape { sphere, ellipsoid, box };

}  // namespace talus
