#include "io/option_checks.hpp"

#include <sstream>

#include "analysis/equilibrium.hpp"
#include "core/error.hpp"

namespace ashlar {

void check_color(const Rgb& color, const std::string& what, const std::string& caller) {
  for (const double component : {color.r, color.g, color.b, color.a}) {
    if (!(component >= 0.0 && component <= 1.0)) {
      std::ostringstream message;
      message << caller << ": " << what << " must have components in [0, 1], got (" << color.r
              << ", " << color.g << ", " << color.b << ", " << color.a << ")";
      throw InvalidArgument(message.str());
    }
  }
}

void check_block_colors(const Structure& structure, const std::vector<Rgb>& colors,
                        const std::string& caller) {
  if (structure.size() == 0) throw InvalidArgument(caller + ": the structure has no blocks");
  if (!colors.empty() && colors.size() != static_cast<size_t>(structure.size())) {
    throw InvalidArgument(caller + ": block_colors has " + std::to_string(colors.size()) +
                          " colours but the structure has " + std::to_string(structure.size()) +
                          " blocks (give one per block, or none)");
  }
  for (size_t i = 0; i < colors.size(); ++i) check_color(colors[i], "colour " + std::to_string(i + 1), caller);
}

void check_result_of_structure(const Structure& structure, const EquilibriumResult* result,
                               bool forces, bool thrust, const ContactOptions& contact,
                               const std::string& caller) {
  if ((forces || thrust) && !result) {
    throw InvalidArgument(caller + ": " + (forces ? "forces" : "thrust") +
                          " needs the result of an analysis of the structure (result = r)");
  }
  if (!result) return;
  const size_t blocks = result->block_tension.size();
  if (blocks != static_cast<size_t>(structure.size())) {
    throw InvalidArgument(caller + ": the result is of a structure with " +
                          std::to_string(blocks) + " blocks, this one has " +
                          std::to_string(structure.size()));
  }
  const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces(contact);
  const std::vector<Interface>& interfaces = *interfaces_list;
  bool same = interfaces.size() == result->interfaces.size();
  for (size_t i = 0; same && i < interfaces.size(); ++i) {
    same = interfaces[i].a == result->interfaces[i].a && interfaces[i].b == result->interfaces[i].b;
  }
  if (!same) {
    throw InvalidArgument(caller + ": the result's " + std::to_string(result->interfaces.size()) +
                          " interfaces are not this structure's " +
                          std::to_string(interfaces.size()) + "; " + caller +
                          " the structure that was analysed, with the analysis's contact "
                          "tolerance");
  }
}

}  // namespace ashlar
