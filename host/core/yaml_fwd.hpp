// yaml-cpp's node, declared for the headers that only take one by reference (yaml-cpp ships no forward
// header): what includes them need not parse yaml-cpp unless it reads YAML itself.
#pragma once

namespace YAML {
class Node;
}  // namespace YAML
