#include "scene/input_fingerprint.hpp"

#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "hydro/initial_conditions.hpp"
#include "md_bridge/particle_engine_registry.hpp"
#include "scene/case_config.hpp"
#include "scene/hydro_scene.hpp"
#include "scene/md_scene.hpp"

namespace granvv::app {
namespace {

using nlohmann::json;
using DigestContext = std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)>;

DigestContext sha256_context() {
  DigestContext ctx(EVP_MD_CTX_new(), &EVP_MD_CTX_free);
  if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256 is not available");
  }
  return ctx;
}

std::string hex_digest(EVP_MD_CTX* ctx) {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int length = 0;
  EVP_DigestFinal_ex(ctx, digest, &length);
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < length; ++i) {
    out += hex[digest[i] >> 4];
    out += hex[digest[i] & 15];
  }
  return out;
}

// The first characters of a digest, enough to tell two apart in a message.
std::string short_digest(const json& digest) {
  const std::string d = digest.is_string() ? digest.get<std::string>() : std::string("none");
  return d.size() > 12 ? d.substr(0, 12) + "..." : d;
}

bool in_tables(const std::string& key, const std::vector<std::string>& tables) {
  for (const auto& table : tables) {
    if (key.size() > table.size() && key.compare(0, table.size(), table) == 0 &&
        key[table.size()] == '.')
      return true;
  }
  return false;
}

bool is_fingerprint(const json& j) {
  return j.is_object() && j.contains("case") && j["case"].is_object() && j.contains("files") &&
         j["files"].is_array();
}

// The first difference of two fingerprints (json::exception where `recorded` has other types).
std::string first_difference(const json& recorded, const json& now) {
  std::map<std::string, std::string> before;
  for (const auto& [key, value] : recorded["case"].items())
    before[key] = value.is_string() ? value.get<std::string>() : value.dump();
  for (const auto& [key, value] : now["case"].items()) {
    const auto found = before.find(key);
    const std::string was = found == before.end() ? "(absent)" : found->second;
    if (was != value.get<std::string>())
      return key + " = " + was + " then, " + value.get<std::string>() + " now";
    before.erase(key);
  }
  if (!before.empty())
    return before.begin()->first + " = " + before.begin()->second + " then, absent now";
  const json& was = recorded["files"];
  const json& is = now["files"];
  for (std::size_t i = 0; i < is.size(); ++i) {
    const std::string path = is[i]["path"].get<std::string>();
    if (i >= was.size() || !was[i].is_object() || was[i].value("path", "") != path)
      return "the file " + path + " was not read then";
    if (was[i].value("sha256", "") != is[i]["sha256"].get<std::string>())
      return "the file " + path + " changed (sha256 " + short_digest(was[i]["sha256"]) + " then, " +
             short_digest(is[i]["sha256"]) + " now)";
  }
  if (was.size() > is.size()) return "a file read then is not read now";
  return "";
}

}  // namespace

std::string text_sha256(std::string_view bytes) {
  const DigestContext ctx = sha256_context();
  EVP_DigestUpdate(ctx.get(), bytes.data(), bytes.size());
  return hex_digest(ctx.get());
}

std::string file_sha256(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  const DigestContext ctx = sha256_context();
  std::array<char, 1 << 16> buffer;
  while (in) {
    in.read(buffer.data(), buffer.size());
    if (in.gcount() > 0) EVP_DigestUpdate(ctx.get(), buffer.data(), std::size_t(in.gcount()));
  }
  if (in.bad()) throw std::runtime_error("cannot read " + file.string());
  return hex_digest(ctx.get());
}

const std::set<std::string>& keys_outside_the_results() {
  static const std::set<std::string> keys{"md.checkpoint_interval", "md.accept_long_run",
                                          "hydro.progress_seconds"};
  return keys;
}

json input_fingerprint(const CaseConfig& config, const std::vector<std::string>& ignored_tables) {
  json values = json::object();
  std::string text;
  for (const auto& [key, value] : config.flattened()) {
    if (keys_outside_the_results().count(key) || in_tables(key, ignored_tables)) continue;
    values[key] = value;
    text += key + " = " + value + "\n";
  }
  std::vector<std::string> paths = hydro::initial_files(initial_parameters_from(config));
  // The particles another program wrote, where the case's engine replays them.
  if (config.boolean("md.enabled")) {
    const std::string engine = config.string("md.engine");
    md::EngineSettings settings;
    md::EngineTexts texts;
    read_engine_keys(config, engine, settings, texts);
    try {
      const auto given = md::engine_input_files(engine, texts);
      paths.insert(paths.end(), given.begin(), given.end());
    } catch (const std::invalid_argument&) {  // refused when the run reads them
    }
  }
  json files = json::array();
  for (const auto& path : paths) {
    std::string digest;
    try {
      digest = file_sha256(path);
    } catch (const std::exception&) {
      digest = "unreadable";
    }
    files.push_back({{"path", path}, {"sha256", digest}});
  }
  return {{"case", values}, {"case_sha256", text_sha256(text)}, {"files", files}};
}

std::string fingerprint_difference(const json& recorded, const json& now) {
  if (!is_fingerprint(recorded)) return "no fingerprint of its inputs";
  try {
    return first_difference(recorded, now);
  } catch (const json::exception&) {
    return "a damaged fingerprint of its inputs";
  }
}
}  // namespace granvv::app
