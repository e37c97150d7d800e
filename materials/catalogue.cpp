#include "materials/catalogue.h"

#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>

#include "core/base/data_path.h"
#include "core/base/error.h"
#include "core/base/table_file.h"

namespace prism {

struct MaterialCatalogue::Impl {
  std::filesystem::path file;
  nlohmann::json index;
  std::map<std::string, CatalogueEntry, std::less<>> entries;
  mutable std::mutex mutex;
  mutable std::map<std::string, MeasuredMetal, std::less<>> metals;  // tables read so far

  const nlohmann::json& record(std::string_view key, bool metal) const {
    const auto it = entries.find(key);
    if (it == entries.end() || it->second.metal != metal) {
      std::string list;
      for (const auto& [k, e] : entries)
        if (e.metal == metal) list += " " + k;
      fail("{}: no {} named '{}'; the catalogue has:{}", file.string(), metal ? "metal" : "dielectric", key, list);
    }
    return index[metal ? "metals" : "dielectrics"][std::string(key)];
  }
};

MaterialCatalogue::MaterialCatalogue(const std::filesystem::path& index_file) : impl_(std::make_unique<Impl>()) {
  impl_->file = index_file;
  std::ifstream in(index_file);
  if (!in) fail("{}: cannot open the material catalogue", index_file.string());
  try {
    impl_->index = nlohmann::json::parse(in);
    for (const char* group : {"metals", "dielectrics"})
      for (const auto& [key, value] : impl_->index.at(group).items())
        impl_->entries[key] = {key, value.at("name").get<std::string>(), value.at("source").get<std::string>(),
                               std::string(group) == "metals"};
  } catch (const nlohmann::json::exception& e) {
    fail("{}: malformed material catalogue: {}", index_file.string(), e.what());
  }
}

MaterialCatalogue::~MaterialCatalogue() = default;

const MaterialCatalogue& MaterialCatalogue::standard() {
  static const MaterialCatalogue catalogue(data_file("materials/catalogue.json"));
  return catalogue;
}

MeasuredMetal MaterialCatalogue::metal(std::string_view key) const {
  const nlohmann::json& rec = impl_->record(key, true);
  std::lock_guard lock(impl_->mutex);
  if (const auto it = impl_->metals.find(key); it != impl_->metals.end()) return it->second;
  const auto file = impl_->file.parent_path() / rec.at("nk").get<std::string>();
  const NumericTable table = read_numeric_table(file);
  const auto& l = table.column("wavelength_nm");
  const auto as_float = [](const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); };
  MeasuredMetal m{TabulatedSpectrum(as_float(l), as_float(table.column("n"))),
                  TabulatedSpectrum(as_float(l), as_float(table.column("k"))), std::string(key)};
  impl_->metals.emplace(std::string(key), m);
  return m;
}

IorModel MaterialCatalogue::dielectric(std::string_view key) const {
  const nlohmann::json& rec = impl_->record(key, false);
  try {
    if (rec.contains("constant")) return ConstantIor{rec.at("constant").get<float>()};
    const auto& s = rec.at("sellmeier");
    SellmeierIor m{s.value("A", 0.f), s.at("B").get<std::vector<float>>(), s.at("C").get<std::vector<float>>()};
    if (m.b.size() != m.c.size()) fail("{}: '{}': Sellmeier B and C differ in length", impl_->file.string(), key);
    return m;
  } catch (const nlohmann::json::exception& e) {
    fail("{}: dielectric '{}': {}", impl_->file.string(), key, e.what());
  }
}

const CatalogueEntry& MaterialCatalogue::entry(std::string_view key) const {
  const auto it = impl_->entries.find(key);
  if (it == impl_->entries.end()) {
    std::string list;
    for (const auto& [k, e] : impl_->entries) list += " " + k;
    fail("{}: no material named '{}'; the catalogue has:{}", impl_->file.string(), key, list);
  }
  return it->second;
}

std::vector<CatalogueEntry> MaterialCatalogue::entries() const {
  std::vector<CatalogueEntry> out;
  for (const auto& [k, e] : impl_->entries) out.push_back(e);
  return out;
}

}  // namespace prism
