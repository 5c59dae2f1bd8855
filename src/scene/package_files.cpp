#include "scene/package_files.h"

#include <zip.h>

#include <algorithm>
#include <map>
#include <utility>

#include "common/error.h"
#include "common/input_file.h"
#include "common/resource_limits.h"

namespace vt {
namespace {

std::string libzipMessage(int code) {
  zip_error_t error;
  zip_error_init_with_code(&error, code);
  std::string message = zip_error_strerror(&error);
  zip_error_fini(&error);
  return message;
}

// One open archive, from a file or from memory; closing it releases its file descriptor.
class ZipArchive {
 public:
  explicit ZipArchive(std::filesystem::path path) : path_(std::move(path)) {
    int code = 0;
    // A FIFO or a device would be read without end; a missing file is libzip's to report.
    if (std::filesystem::exists(path_)) requireRegularFile(path_, "zip archive");
    // No ZIP_CHECKCONS: the game's own reader is lenient, and a damaged entry still fails on read.
    zip_ = zip_open(path_.c_str(), ZIP_RDONLY, &code);
    if (zip_ == nullptr)
      throw InputError(path_, "not a readable zip archive: " + libzipMessage(code));
  }
  // The archive reads `bytes` in place: the vector's buffer moves with this object, never copied.
  ZipArchive(std::filesystem::path name, std::vector<uint8_t> bytes)
      : path_(std::move(name)), memory_(std::move(bytes)) {
    zip_error_t error;
    zip_error_init(&error);
    zip_source_t* source = zip_source_buffer_create(memory_.data(), memory_.size(), 0, &error);
    if (source != nullptr) {
      zip_ = zip_open_from_source(source, ZIP_RDONLY, &error);
      if (zip_ == nullptr) zip_source_free(source);  // still ours when the open failed
    }
    const std::string message = zip_error_strerror(&error);
    zip_error_fini(&error);
    if (zip_ == nullptr) throw InputError(path_, "not a readable zip archive: " + message);
  }
  ~ZipArchive() {
    // A read-only archive has nothing to write back, so zip_discard cannot fail.
    if (zip_ != nullptr) zip_discard(zip_);
  }
  ZipArchive(ZipArchive&& other) noexcept
      : path_(std::move(other.path_)),
        memory_(std::move(other.memory_)),
        zip_(std::exchange(other.zip_, nullptr)) {}
  ZipArchive& operator=(ZipArchive&&) = delete;
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  const std::filesystem::path& path() const { return path_; }
  zip_t* handle() const { return zip_; }

 private:
  std::filesystem::path path_;
  std::vector<uint8_t> memory_;  // the archive's bytes when it is held in memory
  zip_t* zip_ = nullptr;
};

}  // namespace

std::string packageNameKey(std::string_view name) {
  std::string key(name);
  for (char& c : key) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    if (c == '\\') c = '/';
  }
  return key;
}

struct PackageFiles::Archives {
  struct Entry {
    size_t archive;      // index into `archives`
    zip_uint64_t index;  // the entry's index in that archive
    std::string name;    // as stored
  };
  std::vector<ZipArchive> archives;
  std::map<std::string, Entry> entries;  // by packageNameKey; the last archive to add a name wins

  // Opens `archive` after the others: its files override theirs.
  void add(ZipArchive archive) {
    const ZipArchive& added = archives.emplace_back(std::move(archive));
    const zip_int64_t count = zip_get_num_entries(added.handle(), 0);
    if (count < 0) throw InputError(added.path(), "cannot count the archive's entries");
    for (zip_uint64_t i = 0; i < static_cast<zip_uint64_t>(count); ++i) {
      const char* stored = zip_get_name(added.handle(), i, ZIP_FL_ENC_GUESS);
      if (stored == nullptr)
        throw InputError(added.path(), "entry " + std::to_string(i) + " has an unreadable name");
      const std::string name = stored;
      if (name.empty() || name.back() == '/' || name.back() == '\\') continue;  // a folder
      entries.insert_or_assign(packageNameKey(name), Entry{archives.size() - 1, i, name});
    }
  }

  const Entry* lookup(std::string_view name) const {
    const auto it = entries.find(packageNameKey(name));
    return it == entries.end() ? nullptr : &it->second;
  }

  // "<first> ... <last>" for the message about a name no archive holds.
  std::string summary() const {
    if (archives.empty()) return "no archives";
    if (archives.size() == 1) return archives.front().path().string();
    return std::to_string(archives.size()) + " archives, " + archives.front().path().string() +
           " ... " + archives.back().path().string();
  }
};

PackageFiles::PackageFiles() : archives_(std::make_unique<Archives>()) {}

PackageFiles::PackageFiles(const std::vector<std::filesystem::path>& archives) : PackageFiles() {
  archives_->archives.reserve(archives.size());
  for (const auto& path : archives) archives_->add(ZipArchive(path));
}

PackageFiles PackageFiles::fromMemory(const std::filesystem::path& name,
                                      std::vector<uint8_t> archive) {
  PackageFiles files;
  files.archives_->add(ZipArchive(name, std::move(archive)));
  return files;
}

PackageFiles PackageFiles::fromFolders(const std::vector<std::filesystem::path>& folders) {
  std::vector<std::filesystem::path> archives;
  for (const auto& folder : folders) {
    std::error_code error;
    if (!std::filesystem::is_directory(folder, error))
      throw InputError(folder, "not a folder of .pk3 archives");
    std::vector<std::filesystem::path> found;
    for (const auto& item : std::filesystem::directory_iterator(folder)) {
      if (!item.is_directory() && packageNameKey(item.path().extension().string()) == ".pk3")
        found.push_back(item.path());
    }
    // The game sorts without regard to case (ioquake3's FS_SortFileList).
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
      return packageNameKey(a.filename().string()) < packageNameKey(b.filename().string());
    });
    archives.insert(archives.end(), found.begin(), found.end());
  }
  return PackageFiles(archives);
}

PackageFiles::PackageFiles(PackageFiles&&) noexcept = default;
PackageFiles& PackageFiles::operator=(PackageFiles&&) noexcept = default;
PackageFiles::~PackageFiles() = default;

std::optional<std::string> PackageFiles::find(std::string_view name) const {
  const Archives::Entry* entry = archives_->lookup(name);
  if (entry == nullptr) return std::nullopt;
  return entry->name;
}

std::vector<uint8_t> PackageFiles::read(std::string_view name, uint64_t limit) const {
  const Archives::Entry* entry = archives_->lookup(name);
  if (entry == nullptr)
    throw InputError(std::string(name), "no such file in " + archives_->summary());
  const ZipArchive& archive = archives_->archives[entry->archive];
  const auto fail = [&](const std::string& problem) {
    return InputError(archive.path(), "entry '" + entry->name + "': " + problem);
  };
  zip_stat_t stat;
  zip_stat_init(&stat);
  if (zip_stat_index(archive.handle(), entry->index, 0, &stat) != 0 ||
      (stat.valid & ZIP_STAT_SIZE) == 0)
    throw fail(zip_strerror(archive.handle()));
  if (stat.size > limit)
    throw limitError(archive.path(), "entry '" + entry->name + "'", stat.size, limit, " bytes");
  zip_file_t* file = zip_fopen_index(archive.handle(), entry->index, 0);
  if (file == nullptr) throw fail(zip_strerror(archive.handle()));
  // Read to the end rather than trusting the declared size (a damaged entry may lie), but never
  // past it: a lying entry could inflate without bound. libzip checks the CRC at the end.
  std::vector<uint8_t> bytes;
  bytes.reserve(std::min<zip_uint64_t>(stat.size, zip_uint64_t{1} << 26));
  uint8_t chunk[1 << 16];
  for (;;) {
    const zip_int64_t n = zip_fread(file, chunk, sizeof chunk);
    if (n < 0) {
      const std::string message = zip_file_strerror(file);
      zip_fclose(file);
      throw fail("cannot inflate: " + message);
    }
    if (n == 0) break;
    bytes.insert(bytes.end(), chunk, chunk + n);
    if (bytes.size() > stat.size) break;
  }
  zip_fclose(file);
  if (bytes.size() > stat.size)
    throw fail("inflates to more than the " + std::to_string(stat.size) +
               " bytes the directory says");
  if (bytes.size() != stat.size)
    throw fail("inflated to " + std::to_string(bytes.size()) + " bytes, the directory says " +
               std::to_string(stat.size));
  return bytes;
}

std::vector<std::string> PackageFiles::list(std::string_view prefix,
                                            std::string_view suffix) const {
  const std::string prefixKey = packageNameKey(prefix), suffixKey = packageNameKey(suffix);
  std::vector<std::string> names;
  // The map is ordered by key, so the names with the prefix form one run from its lower bound.
  for (auto it = archives_->entries.lower_bound(prefixKey);
       it != archives_->entries.end() && it->first.starts_with(prefixKey); ++it) {
    if (it->first.ends_with(suffixKey)) names.push_back(it->second.name);
  }
  return names;
}

std::string PackageFiles::describe(std::string_view name) const {
  const Archives::Entry* entry = archives_->lookup(name);
  if (entry == nullptr) return std::string(name);
  return archives_->archives[entry->archive].path().string() + ":" + entry->name;
}

}  // namespace vt
