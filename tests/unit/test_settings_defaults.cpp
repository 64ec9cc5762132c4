// The defaults docs/api.md gives for each analysis's options, read from its
// option tables, against the defaults of the settings structs the bindings
// start from; and the status names scripts see, read both ways.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include "analysis/compare_methods.hpp"
#include "analysis/equilibrium.hpp"
#include "analysis/kinematic.hpp"
#include "analysis/load_capacity.hpp"
#include "analysis/load_factor.hpp"
#include "analysis/margin_status.hpp"
#include "analysis/parameter_search.hpp"
#include "analysis/weight_analysis.hpp"
#include "fea/fea.hpp"
#include "fea/fea_mesh.hpp"
#include "io/fea_export.hpp"

using namespace ashlar;

namespace {

std::string api_docs() {
  std::ifstream file(ASHLAR_DOCS "/api.md");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// Per key (`key` in the first cell), the rest of its row: the cells of the
// option tables in the section under `heading`, up to the next heading.
std::map<std::string, std::vector<std::string>> option_rows(const std::string& heading) {
  const std::string docs = api_docs();
  const size_t from = docs.find("\n" + heading + "\n");
  if (from == std::string::npos) return {};
  const size_t to = docs.find("\n#", from + 1);
  std::istringstream section(docs.substr(from, to == std::string::npos ? std::string::npos : to - from));
  std::map<std::string, std::vector<std::string>> rows;
  const std::regex row(R"(^\| `(\w+)` \|(.*)\|\s*$)");
  std::smatch match;
  for (std::string line; std::getline(section, line);) {
    if (!std::regex_match(line, match, row)) continue;
    std::vector<std::string> cells;
    std::istringstream rest(match[2].str());
    for (std::string cell; std::getline(rest, cell, '|');) {
      cells.push_back(std::regex_replace(cell, std::regex(R"(^\s+|\s+$)"), ""));
    }
    rows[match[1].str()] = cells;
  }
  return rows;
}

// The documented default of `key` (the row's second cell) in the section.
std::string documented(const std::string& heading, const std::string& key) {
  const auto rows = option_rows(heading);
  const auto found = rows.find(key);
  return found == rows.end() || found->second.empty() ? "(not documented)" : found->second[0];
}

// The first number in a cell ("1e-6; 1e-3 with ..." -> 1e-6), NaN if none.
double number_in(const std::string& cell, const std::string& after = "") {
  const size_t start = after.empty() ? 0 : cell.find(after);
  if (start == std::string::npos) return std::nan("");
  std::smatch match;
  const std::string rest = cell.substr(start + after.size());
  if (!std::regex_search(rest, match, std::regex(R"([-+]?\d+(\.\d+)?(e[-+]?\d+)?)"))) return std::nan("");
  return std::stod(match[0].str());
}

// The number written just before `before` in the cell.
double number_before(const std::string& cell, const std::string& before) {
  std::smatch match;
  const std::regex pattern(R"(([-+]?\d+(\.\d+)?(e[-+]?\d+)?) )" + before);
  if (!std::regex_search(cell, match, pattern)) return std::nan("");
  return std::stod(match[1].str());
}

const char* kAnalyze = "## Equilibrium analysis";
const char* kLoadFactor = "### Load factor";
const char* kFrictionDemand = "### Friction demand";
const char* kGeometricFactor = "### Geometric factor of safety";
const char* kRefine = "### Refining a discretisation";
const char* kWeights = "## Weights: sensitivity, load capacity, necessary and important weights";
const char* kFea = "## Elastic FEA";

}  // namespace

TEST(DocumentedDefaults, Analyze) {
  const AnalysisSettings settings;
  EXPECT_EQ(number_in(documented(kAnalyze, "friction")), settings.problem.friction);
  EXPECT_EQ(number_in(documented(kAnalyze, "friction_sides")), settings.problem.friction_sides);
  EXPECT_EQ(documented(kAnalyze, "friction_model"),
            std::string("`\"") + kFrictionModelNames.name(settings.problem.friction_model) + "\"`");
  EXPECT_EQ(number_in(documented(kAnalyze, "tension_weight")), settings.problem.tension_weight);
  EXPECT_EQ(number_in(documented(kAnalyze, "force_weight")), settings.problem.force_weight);
  EXPECT_EQ(number_in(documented(kAnalyze, "tolerance")), settings.solver.tolerance);
  EXPECT_EQ(number_in(documented(kAnalyze, "max_iterations")), settings.solver.max_iterations);
  EXPECT_EQ(number_in(documented(kAnalyze, "stable_tolerance")), settings.stable_tolerance);
  EXPECT_EQ(documented(kAnalyze, "verdict_only"), settings.verdict_only ? "true" : "false");
  EXPECT_EQ(documented(kAnalyze, "method"),
            std::string("`\"") + kAnalysisMethodNames.name(settings.method) + "\"`");
}

TEST(DocumentedDefaults, LoadFactor) {
  const LoadFactorSettings settings;
  EXPECT_EQ(documented(kLoadFactor, "load"), std::string("`\"") + kLoadPatternNames.name(settings.pattern) + "\"`");
  const Vec3& d = settings.direction;
  std::ostringstream direction;
  direction << "`{" << d.x() << ", " << d.y() << ", " << d.z() << "}`";
  EXPECT_EQ(documented(kLoadFactor, "direction"), direction.str());
  EXPECT_EQ(number_in(documented(kLoadFactor, "bracket_tolerance")), KinematicLoadFactorSettings{}.bracket_tolerance);
}

TEST(DocumentedDefaults, FrictionDemand) {
  const std::string cell = documented(kFrictionDemand, "bracket_tolerance");
  EXPECT_EQ(number_in(cell), FrictionDemandSettings{}.bracket_tolerance) << cell;
  EXPECT_EQ(number_before(cell, "with `method = \"kinematic\"`"), KinematicFrictionDemandSettings{}.bracket_tolerance)
      << cell;
}

TEST(DocumentedDefaults, GeometricFactor) {
  const ThresholdSettings settings;
  EXPECT_EQ(number_in(documented(kGeometricFactor, "bracket_tolerance")), settings.bracket_tolerance);
  EXPECT_EQ(number_in(documented(kGeometricFactor, "max_analyses")), settings.max_evaluations);
  EXPECT_EQ(number_before(documented(kGeometricFactor, "upper"), "× `value`"), kThresholdCeilingMultiple);
  // The floor is in the meaning: "values down to `value` × 1e-6 are tried".
  const auto lower = option_rows(kGeometricFactor)["lower"];
  ASSERT_EQ(lower.size(), 2u);
  EXPECT_EQ(number_in(lower[1], "`value` ×"), kThresholdFloorFraction) << lower[1];
}

TEST(DocumentedDefaults, Refine) {
  const RefineSettings settings;
  EXPECT_EQ(number_in(documented(kRefine, "tolerance")), settings.tolerance);
  EXPECT_EQ(number_in(documented(kRefine, "start")), settings.start);
  EXPECT_EQ(number_in(documented(kRefine, "growth")), settings.growth);
  EXPECT_EQ(number_in(documented(kRefine, "max")), settings.max);
  EXPECT_EQ(number_in(documented(kRefine, "confirm")), settings.confirm);
}

TEST(DocumentedDefaults, FeaVtuExport) {
  EXPECT_EQ(documented(kFea, "format"), std::string("`\"") + kVtuFormatNames.name(FeaVtuOptions{}.format) + "\"`");
}

TEST(DocumentedDefaults, LoadCapacityAndImportantWeights) {
  EXPECT_EQ(number_in(documented(kWeights, "threads")), LoadCapacitySettings{}.threads);
  EXPECT_EQ(number_in(documented(kWeights, "threads")), ImportantWeightsSettings{}.threads);
  EXPECT_EQ(documented(kWeights, "symmetry"), LoadCapacitySettings{}.use_symmetry ? "true" : "false");
  EXPECT_EQ(documented(kWeights, "symmetry"), ImportantWeightsSettings{}.use_symmetry ? "true" : "false");
}

TEST(DocumentedDefaults, Fea) {
  const FeaSettings settings;
  EXPECT_EQ(number_in(documented(kFea, "young")), settings.material.young);
  EXPECT_EQ(number_in(documented(kFea, "poisson")), settings.material.poisson);
  EXPECT_EQ(number_in(documented(kFea, "refine")), kDefaultRefine);
  EXPECT_EQ(documented(kFea, "method"), std::string("`\"") + kFeaContactModelNames.name(settings.method) + "\"`");
  EXPECT_EQ(documented(kFea, "relax"), settings.relax ? "`true`" : "`false`");
  EXPECT_EQ(number_in(documented(kFea, "max_relax_iterations")), settings.max_relax_iterations);
  EXPECT_EQ(documented(kFea, "release"), std::string("`\"") + kFeaReleaseNames.name(settings.release) + "\"`");
  EXPECT_EQ(number_in(documented(kFea, "tension_tolerance")), settings.tension_tolerance);
  EXPECT_EQ(number_in(documented(kFea, "max_displacement")), settings.max_displacement);
  EXPECT_EQ(documented(kFea, "stresses"), settings.stresses ? "`true`" : "`false`");
}

// Every status name reads back as its value, and no two values share one.
template <class Enum, std::size_t Count>
void expect_both_ways(const EnumNames<Enum, Count>& names) {
  for (const auto& [value, name] : names.entries) {
    const std::optional<Enum> parsed = names.parse(name);
    ASSERT_TRUE(parsed.has_value()) << name;
    EXPECT_TRUE(*parsed == value) << name;
    EXPECT_STREQ(names.name(value), name);
  }
}

TEST(OutcomeNames, ReadBothWays) {
  expect_both_ways(kMarginStatusNames);
  expect_both_ways(kImportantWeightsStatusNames);
  expect_both_ways(kVerdictNames);
  expect_both_ways(kDecidedByNames);
}

TEST(OutcomeNames, AreTheStringsScriptsCompare) {
  // Scripts written against the earlier free-text statuses compare these.
  EXPECT_STREQ(kMarginStatusNames.name(MarginStatus::numerical_difficulties), "numerical difficulties");
  EXPECT_STREQ(kMarginStatusNames.name(MarginStatus::unexpected), "unexpected simplex status");
  EXPECT_STREQ(kMarginStatusNames.name(MarginStatus::no_verdict), "no verdict");
  EXPECT_STREQ(kMarginStatusNames.name(MarginStatus::stopped), "stopped");
  EXPECT_STREQ(kImportantWeightsStatusNames.name(ImportantWeightsStatus::done), "done");
}
