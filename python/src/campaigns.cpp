// ladarsim.Campaign: a campaign directory (`ladarsim campaign`), its sequences in the index's
// order, each with what was drawn for it and its dataset, read when asked for.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.h"
#include "datasets.h"
#include "json_objects.h"
#include "ladarsim/campaign/campaign_index.h"
#include "ladarsim/core/json_file.h"

namespace ladarsim::python {

namespace {

struct CampaignSequence {
    int id = 0;
    std::string split;
    std::filesystem::path path;
    nlohmann::json entry;  ///< its entry in campaign.json
};

class Campaign {
public:
    Campaign(const std::filesystem::path& dir, const std::optional<std::string>& split) : dir_(dir) {
        if (split && *split != "train" && *split != "val" && *split != "test")
            throw py::value_error("split must be 'train', 'val' or 'test', not '" + *split + "'");
        const std::vector<campaign::IndexedSequence> listed = campaign::read_campaign_index(dir);
        index_ = read_json(dir / "campaign.json");
        for (std::size_t i = 0; i < listed.size(); ++i)
            if (!split || listed[i].split == *split)
                sequences_.push_back({listed[i].id, listed[i].split, listed[i].directory, index_["sequences"][i]});
    }
    std::size_t size() const { return sequences_.size(); }
    const CampaignSequence& at(std::ptrdiff_t i) const {
        const auto n = static_cast<std::ptrdiff_t>(sequences_.size());
        if (i < 0) i += n;
        if (i < 0 || i >= n) throw py::index_error("campaign index out of range");
        return sequences_[static_cast<std::size_t>(i)];
    }
    const std::filesystem::path& dir() const { return dir_; }
    const nlohmann::json& index() const { return index_; }

private:
    std::filesystem::path dir_;
    nlohmann::json index_;
    std::vector<CampaignSequence> sequences_;
};

}  // namespace

void bind_campaigns(py::module_& m) {
    py::class_<CampaignSequence>(m, "CampaignSequence", "One sequence of a campaign: its entry in campaign.json and its dataset.")
        .def_readonly("id", &CampaignSequence::id)
        .def_readonly("split", &CampaignSequence::split, "'train', 'val' or 'test'")
        .def_readonly("path", &CampaignSequence::path, "Its dataset directory.")
        .def_property_readonly("seed", [](const CampaignSequence& s) { return s.entry.at("seed").get<std::uint64_t>(); },
                               "Its render seed.")
        .def_property_readonly("sampled", [](const CampaignSequence& s) { return to_python(s.entry.at("sampled")); },
                               "What was drawn for it (docs/campaign.md), as a dict.")
        .def_property_readonly("returns_by_class",
                               [](const CampaignSequence& s) { return to_python(s.entry.at("returns_by_class")); })
        .def_property_readonly("scenario",
                               [](const CampaignSequence& s) {
                                   return to_python(read_json(s.path.parent_path() / (s.path.filename().string() + ".json")));
                               },
                               "Its sampled scenario, as a dict (ladarsim.render takes it).")
        .def_property_readonly("dataset", [](const CampaignSequence& s) { return Dataset(s.path); },
                               "Its frames: a ladarsim.Dataset.")
        .def("__repr__", [](const CampaignSequence& s) {
            return "<ladarsim.CampaignSequence " + std::to_string(s.id) + " (" + s.split + "): " + s.path.string() + ">";
        });

    py::class_<Campaign>(m, "Campaign", R"(A rendered campaign (`ladarsim campaign`, docs/campaign.md): its sequences in the order of
campaign.json, or of one split only (split="train", "val" or "test"). len(), c[i], iteration
give CampaignSequence objects; .index is campaign.json as a dict.)")
        .def(py::init<std::filesystem::path, std::optional<std::string>>(), py::arg("dir"), py::arg("split") = py::none())
        .def("__len__", &Campaign::size)
        .def("__getitem__", &Campaign::at, py::arg("index"), py::return_value_policy::copy)
        .def("__iter__",
             [](const Campaign& c) {
                 std::vector<CampaignSequence> all;
                 for (std::size_t i = 0; i < c.size(); ++i) all.push_back(c.at(static_cast<std::ptrdiff_t>(i)));
                 return py::iter(py::cast(all));
             })
        .def_property_readonly("path", &Campaign::dir)
        .def_property_readonly("index", [](const Campaign& c) { return to_python(c.index()); }, "campaign.json as a dict.")
        .def("__repr__", [](const Campaign& c) {
            return "<ladarsim.Campaign " + c.dir().string() + ": " + std::to_string(c.size()) + " sequences>";
        });
}

}  // namespace ladarsim::python
