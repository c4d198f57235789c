// Each kind's CSV and summary, for the kind table in kinds.cpp (internal header).
#pragma once
#include "radfmt/kinds.hpp"

#include <ostream>

namespace radfmt::detail {
void mesh_csv(const std::filesystem::path& path, std::ostream& out);
std::string mesh_summary(const std::filesystem::path& path, Header& header);
void form_factor_csv(const std::filesystem::path& path, std::ostream& out);
std::string form_factor_summary(const std::filesystem::path& path, Header& header);
void form_factor_part_csv(const std::filesystem::path& path, std::ostream& out);
std::string form_factor_part_summary(const std::filesystem::path& path, Header& header);
void radiosity_csv(const std::filesystem::path& path, std::ostream& out);
std::string radiosity_summary(const std::filesystem::path& path, Header& header);
void links_csv(const std::filesystem::path& path, std::ostream& out);
std::string links_summary(const std::filesystem::path& path, Header& header);
void luminaires_csv(const std::filesystem::path& path, std::ostream& out);
std::string luminaires_summary(const std::filesystem::path& path, Header& header);
void sky_csv(const std::filesystem::path& path, std::ostream& out);
std::string sky_summary(const std::filesystem::path& path, Header& header);
void annual_csv(const std::filesystem::path& path, std::ostream& out);
std::string annual_summary(const std::filesystem::path& path, Header& header);
} // namespace radfmt::detail
