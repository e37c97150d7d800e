#pragma once
// The named optical materials Prism ships (data/materials/catalogue.json): measured metals
// (n, k tables) and dielectrics (dispersion formulas or constants), with their sources. The
// index is read on first use; a metal's table is read only when that metal is asked for.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "materials/material.h"

namespace prism {

struct CatalogueEntry {
  std::string key, name, source;
  bool metal;
};

class MaterialCatalogue {
 public:
  explicit MaterialCatalogue(const std::filesystem::path& index_file);
  ~MaterialCatalogue();
  static const MaterialCatalogue& standard();  // data/materials/catalogue.json

  // Throws prism::Error listing the available keys when there is no such material.
  MeasuredMetal metal(std::string_view key) const;
  IorModel dielectric(std::string_view key) const;

  const CatalogueEntry& entry(std::string_view key) const;
  std::vector<CatalogueEntry> entries() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace prism
