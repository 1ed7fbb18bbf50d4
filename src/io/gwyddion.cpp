// Gwyddion backend: every format a Gwyddion file module loads (SPM, profilometry, confocal,
// interferometry), read through Gwyddion's own libraries, loaded at run time with dlopen() so
// that frictal builds and runs without them (the error for such a file then names the
// packages). Headless: GTK is never initialised; what gwy_file_load() needs is
//   gwy_type_init(), gwy_draw_type_init(), gwy_process_type_init(), the gradient resources,
//   and gwy_module_register_modules() on the file-module directory,
// with libgwyapp2 loaded RTLD_GLOBAL first (the file modules take gwy_app_* symbols from the
// process without linking libgwyapp2 themselves). Checked on Debian 12's Gwyddion 2.62
// (docs/io.md). Gwyddion is not thread-safe: one process-wide mutex serialises every call.
#include <dlfcn.h>
#include <fmt/core.h>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "frictal/io.hpp"
#include "io/readers.hpp"
#include "io/text_util.hpp"

#ifndef FRICTAL_GWYDDION_ENABLED
#define FRICTAL_GWYDDION_ENABLED 0
#endif
#ifndef FRICTAL_GWYDDION_LIBRARY
#define FRICTAL_GWYDDION_LIBRARY "libgwyapp2.so.0"
#endif
#ifndef FRICTAL_GWYDDION_MODULE_DIR
#define FRICTAL_GWYDDION_MODULE_DIR "/usr/lib/x86_64-linux-gnu/gwyddion/modules"
#endif

namespace frictal {
namespace {

// The C ABI of GLib/GObject and Gwyddion 2.x used here (no headers needed at build time).
using GType = unsigned long;
using GQuark = std::uint32_t;
using gboolean = int;
struct GError {
  GQuark domain;
  int code;
  char* message;
};
using GFunc = void (*)(void*, void*);
using GLogFunc = void (*)(const char* domain, int level, const char* message, void* data);
constexpr int kRunNonInteractive = 1;  // GWY_RUN_NONINTERACTIVE
constexpr int kOpLoad = 1 << 1;        // GWY_FILE_OPERATION_LOAD
constexpr int kOpSave = 1 << 2;        // GWY_FILE_OPERATION_SAVE
constexpr int kOpExport = 1 << 3;      // GWY_FILE_OPERATION_EXPORT
constexpr int kUnitFormatPlain = 1;    // GWY_SI_UNIT_FORMAT_PLAIN

struct ModuleFailure {
  const char* filename;
  const char* modname;
  const char* err_message;
  int err_domain, err_code;
};

#define FRICTAL_GWY_FUNCS(X)                                                         \
  X(void, gwy_type_init, (void))                                                     \
  X(void, gwy_draw_type_init, (void))                                                \
  X(void, gwy_process_type_init, (void))                                             \
  X(GType, gwy_gradient_get_type, (void))                                            \
  X(void*, g_type_class_ref, (GType))                                                \
  X(void, gwy_resource_class_load, (void*))                                          \
  X(void, gwy_module_register_modules, (const char**))                               \
  X(void, gwy_module_failure_foreach, (GFunc, void*))                                \
  X(void, gwy_file_func_foreach, (GFunc, void*))                                     \
  X(int, gwy_file_func_get_operations, (const char*))                                \
  X(const char*, gwy_file_func_get_description, (const char*))                       \
  X(const char*, gwy_file_detect, (const char*, gboolean, int))                      \
  X(void*, gwy_file_load_with_func, (const char*, int, const char**, GError**))      \
  X(int, gwy_file_save_with_func, (void*, const char*, int, const char**, GError**)) \
  X(const char**, gwy_container_keys_by_name, (void*))                               \
  X(unsigned, gwy_container_get_n_items, (void*))                                    \
  X(gboolean, gwy_container_gis_object, (void*, GQuark, void*))                      \
  X(gboolean, gwy_container_gis_string, (void*, GQuark, const unsigned char**))      \
  X(void*, gwy_container_new, (void))                                                \
  X(void, gwy_container_set_object, (void*, GQuark, void*))                          \
  X(void, gwy_container_set_const_string, (void*, GQuark, const unsigned char*))     \
  X(GQuark, g_quark_from_string, (const char*))                                      \
  X(gboolean, g_type_check_instance_is_a, (void*, GType))                            \
  X(void, g_object_unref, (void*))                                                   \
  X(void, g_object_get, (void*, const char*, ...))                                   \
  X(void, g_free, (void*))                                                           \
  X(void, g_error_free, (GError*))                                                   \
  X(GLogFunc, g_log_set_default_handler, (GLogFunc, void*))                          \
  X(GType, gwy_data_field_get_type, (void))                                          \
  X(void*, gwy_data_field_new, (int, int, double, double, gboolean))                 \
  X(int, gwy_data_field_get_xres, (void*))                                           \
  X(int, gwy_data_field_get_yres, (void*))                                           \
  X(double, gwy_data_field_get_xreal, (void*))                                       \
  X(double, gwy_data_field_get_yreal, (void*))                                       \
  X(double, gwy_data_field_get_xoffset, (void*))                                     \
  X(double, gwy_data_field_get_yoffset, (void*))                                     \
  X(void, gwy_data_field_set_xoffset, (void*, double))                               \
  X(void, gwy_data_field_set_yoffset, (void*, double))                               \
  X(const double*, gwy_data_field_get_data_const, (void*))                           \
  X(double*, gwy_data_field_get_data, (void*))                                       \
  X(void*, gwy_data_field_get_si_unit_xy, (void*))                                   \
  X(void*, gwy_data_field_get_si_unit_z, (void*))                                    \
  X(void, gwy_data_field_set_si_unit_xy, (void*, void*))                             \
  X(void, gwy_data_field_set_si_unit_z, (void*, void*))                              \
  X(void*, gwy_si_unit_new, (const char*))                                           \
  X(char*, gwy_si_unit_get_string, (void*, int))                                     \
  X(GType, gwy_graph_model_get_type, (void))                                         \
  X(int, gwy_graph_model_get_n_curves, (void*))                                      \
  X(void*, gwy_graph_model_get_curve, (void*, int))                                  \
  X(int, gwy_graph_curve_model_get_ndata, (void*))                                   \
  X(const double*, gwy_graph_curve_model_get_xdata, (void*))                         \
  X(const double*, gwy_graph_curve_model_get_ydata, (void*))                         \
  X(void, gwy_app_data_browser_set_gui_enabled, (gboolean))                          \
  X(void, gwy_app_data_browser_add, (void*))                                         \
  X(void, gwy_app_data_browser_remove, (void*))                                      \
  X(void, gwy_app_data_browser_select_data_field, (void*, int))

struct Api {
#define FRICTAL_GWY_MEMBER(ret, name, args) ret(*name) args = nullptr;
  FRICTAL_GWY_FUNCS(FRICTAL_GWY_MEMBER)
#undef FRICTAL_GWY_MEMBER
};

struct Backend {
  std::mutex mutex;  // every Gwyddion call holds it
  bool tried = false;
  std::string load_error;  // why the libraries did not load (empty: loaded)
  Api api;
  std::set<std::string> registered;              // module directories registered
  std::map<std::string, std::string> dir_error;  // per directory: why it has no file modules
};

Backend& backend() {
  static Backend b;
  return b;
}

const char* kPackages = "Debian/Ubuntu packages libgwyddion2-0 (libraries) and gwyddion (file modules)";

/// Loads the libraries and initialises the type system once. Caller holds the mutex.
bool load_libraries(Backend& b) {
  if (b.tried) return b.load_error.empty();
  b.tried = true;
#if !FRICTAL_GWYDDION_ENABLED
  b.load_error = "frictal was built without the Gwyddion backend (cmake -DFRICTAL_GWYDDION=OFF)";
  return false;
#else
  // In dependency order, each RTLD_GLOBAL: libgwymodule2 uses libgwydgets2 and libgwyapp2 uses
  // libgwymodule2 without listing them as needed, and the file modules use all of them.
  void* h = nullptr;
  for (const char* lib : {"libgwyddion2.so.0", "libgwyprocess2.so.0", "libgwydraw2.so.0", "libgwydgets2.so.0",
                          "libgwymodule2.so.0", FRICTAL_GWYDDION_LIBRARY}) {
    h = dlopen(lib, RTLD_LAZY | RTLD_GLOBAL);
    if (!h) {
      b.load_error = fmt::format("Gwyddion's libraries are not installed ({}: {})", lib, dlerror());
      return false;
    }
  }
  h = RTLD_DEFAULT;
#define FRICTAL_GWY_LOAD(ret, name, args)                                                     \
  b.api.name = reinterpret_cast<ret(*) args>(dlsym(h, #name));                                \
  if (!b.api.name) {                                                                          \
    b.load_error = fmt::format("Gwyddion's libraries lack {} (version 2.x expected)", #name); \
    return false;                                                                             \
  }
  FRICTAL_GWY_FUNCS(FRICTAL_GWY_LOAD)
#undef FRICTAL_GWY_LOAD
  const Api& a = b.api;
  a.gwy_type_init();
  a.gwy_draw_type_init();
  a.gwy_process_type_init();
  a.gwy_resource_class_load(a.g_type_class_ref(a.gwy_gradient_get_type()));
  a.gwy_app_data_browser_set_gui_enabled(0);
  return true;
#endif
}

std::string module_root(const std::string& dir) { return dir.empty() ? std::string(FRICTAL_GWYDDION_MODULE_DIR) : dir; }

/// Registers <root>/file once. Caller holds the mutex. Returns "" or why not.
std::string ensure_modules(Backend& b, const std::string& root) {
  if (!load_libraries(b)) return b.load_error;
  if (b.registered.count(root)) return "";
  if (auto it = b.dir_error.find(root); it != b.dir_error.end()) return it->second;
  const std::string dir = root + "/file";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    b.dir_error[root] = fmt::format("Gwyddion's file modules are not installed (no directory {})", dir);
    return b.dir_error[root];
  }
  const char* paths[] = {dir.c_str(), nullptr};
  b.api.gwy_module_register_modules(paths);
  int loaders = 0;
  std::pair<Backend*, int*> ctx{&b, &loaders};
  b.api.gwy_file_func_foreach(
      [](void* name, void* data) {
        auto* c = static_cast<std::pair<Backend*, int*>*>(data);
        if (c->first->api.gwy_file_func_get_operations(static_cast<const char*>(name)) & kOpLoad) ++*c->second;
      },
      &ctx);
  if (loaders == 0) {
    b.dir_error[root] = fmt::format("no Gwyddion file module in {} could be loaded", dir);
    return b.dir_error[root];
  }
  b.registered.insert(root);
  return "";
}

std::string unit_string(const Api& a, void* unit) {
  if (!unit) return "";
  char* s = a.gwy_si_unit_get_string(unit, kUnitFormatPlain);
  std::string r = s ? s : "";
  a.g_free(s);
  return r;
}

/// Metres per unit of a Gwyddion unit string ("m", "µm", ...); nullopt if not a length.
std::optional<double> length_scale(const std::string& u) { return io_detail::unit_scale(u); }

/// While alive, GLib messages (Gwyddion's g_warning()s, e.g. "Type `GwySelectionPoint' is
/// unknown") go into `messages` instead of stderr: the library never prints. Caller holds the
/// backend mutex (the handler is process-wide while set).
class LogCapture {
 public:
  explicit LogCapture(const Api& a) : a_(a) { prev_ = a_.g_log_set_default_handler(&LogCapture::handle, this); }
  ~LogCapture() { a_.g_log_set_default_handler(prev_, nullptr); }
  LogCapture(const LogCapture&) = delete;
  LogCapture& operator=(const LogCapture&) = delete;
  /// The messages, each "Gwyddion: <message>" (debug and info messages are dropped).
  std::vector<std::string> take() {
    std::lock_guard lock(mutex_);
    return std::move(messages_);
  }

 private:
  static void handle(const char* domain, int level, const char* message, void* data) {
    constexpr int kDebugOrInfo = (1 << 6) | (1 << 7);  // G_LOG_LEVEL_INFO, G_LOG_LEVEL_DEBUG
    if (level & kDebugOrInfo) return;
    auto* self = static_cast<LogCapture*>(data);
    std::lock_guard lock(self->mutex_);  // modules may log from worker threads
    if (self->messages_.size() < 20)
      self->messages_.push_back(
          fmt::format("{}: {}", domain && *domain ? domain : "GLib", message ? message : "(no message)"));
  }
  const Api& a_;
  GLogFunc prev_ = nullptr;
  std::mutex mutex_;
  std::vector<std::string> messages_;
};

struct Channel {
  ChannelInfo info;
  int id = -1;            // image: the N of /N/data
  void* graph = nullptr;  // curve: its graph model
  int curve = -1;         // curve: index in the graph
};

std::vector<Channel> list_channels(const Api& a, void* c) {
  std::vector<Channel> out;
  const char** keys = a.gwy_container_keys_by_name(c);
  const std::size_t nkeys = a.gwy_container_get_n_items(c);
  std::vector<int> ids;
  std::vector<std::string> graphs;
  for (std::size_t k = 0; keys && k < nkeys && keys[k]; ++k) {
    std::string key = keys[k];
    // "/N/data": an image channel.
    if (key.size() > 6 && key[0] == '/' && key.compare(key.size() - 5, 5, "/data") == 0) {
      const std::string n = key.substr(1, key.size() - 6);
      if (!n.empty() && n.size() < 9 && std::all_of(n.begin(), n.end(), [](char ch) { return ch >= '0' && ch <= '9'; }))
        ids.push_back(std::stoi(n));
    }
    if (key.rfind("/0/graph/graph/", 0) == 0) graphs.push_back(key);
  }
  a.g_free(keys);
  std::sort(ids.begin(), ids.end());
  for (int id : ids) {
    void* f = nullptr;
    if (!a.gwy_container_gis_object(c, a.g_quark_from_string(fmt::format("/{}/data", id).c_str()), &f) || !f ||
        !a.g_type_check_instance_is_a(f, a.gwy_data_field_get_type()))
      continue;
    Channel ch;
    ch.id = id;
    const unsigned char* title = nullptr;
    ch.info.name =
        a.gwy_container_gis_string(c, a.g_quark_from_string(fmt::format("/{}/data/title", id).c_str()), &title) && title
            ? reinterpret_cast<const char*>(title)
            : fmt::format("channel {}", id);
    ch.info.is_map = true;
    ch.info.nx = std::size_t(a.gwy_data_field_get_xres(f));
    ch.info.ny = std::size_t(a.gwy_data_field_get_yres(f));
    ch.info.size_x = a.gwy_data_field_get_xreal(f);
    ch.info.size_y = a.gwy_data_field_get_yreal(f);
    ch.info.xy_unit = unit_string(a, a.gwy_data_field_get_si_unit_xy(f));
    ch.info.z_unit = unit_string(a, a.gwy_data_field_get_si_unit_z(f));
    // Lengths, or no units at all (read like a text column without a unit: metres or --unit).
    ch.info.readable = (length_scale(ch.info.xy_unit) && length_scale(ch.info.z_unit)) ||
                       (ch.info.xy_unit.empty() && ch.info.z_unit.empty());
    out.push_back(ch);
  }
  std::sort(graphs.begin(), graphs.end(), [](const std::string& x, const std::string& y) {
    return x.size() != y.size() ? x.size() < y.size() : x < y;
  });
  for (const auto& g : graphs) {
    void* gm = nullptr;
    if (!a.gwy_container_gis_object(c, a.g_quark_from_string(g.c_str()), &gm) || !gm ||
        !a.g_type_check_instance_is_a(gm, a.gwy_graph_model_get_type()))
      continue;
    void *ux = nullptr, *uy = nullptr;
    char* gtitle = nullptr;
    a.g_object_get(gm, "si-unit-x", &ux, "si-unit-y", &uy, "title", &gtitle, nullptr);
    const std::string sx = unit_string(a, ux), sy = unit_string(a, uy);
    if (ux) a.g_object_unref(ux);
    if (uy) a.g_object_unref(uy);
    const std::string graph_title = gtitle ? gtitle : g;
    a.g_free(gtitle);
    const int n = a.gwy_graph_model_get_n_curves(gm);
    for (int k = 0; k < n; ++k) {
      void* cm = a.gwy_graph_model_get_curve(gm, k);
      Channel ch;
      ch.graph = gm;
      ch.curve = k;
      char* desc = nullptr;
      a.g_object_get(cm, "description", &desc, nullptr);
      ch.info.name = graph_title + (desc && *desc ? fmt::format(": {}", desc) : fmt::format(": curve {}", k));
      a.g_free(desc);
      ch.info.is_map = false;
      ch.info.nx = std::size_t(a.gwy_graph_curve_model_get_ndata(cm));
      ch.info.ny = 1;
      const double* x = a.gwy_graph_curve_model_get_xdata(cm);
      ch.info.size_x = ch.info.nx ? x[ch.info.nx - 1] - x[0] : 0;
      ch.info.xy_unit = sx;
      ch.info.z_unit = sy;
      ch.info.readable = length_scale(sx) && length_scale(sy) && ch.info.nx >= 2;
      out.push_back(ch);
    }
  }
  return out;
}

}  // namespace

bool gwyddion_available(const std::string& module_dir, std::string* why) {
  Backend& b = backend();
  std::lock_guard lock(b.mutex);
  std::string e = ensure_modules(b, module_root(module_dir));
  if (why) *why = e.empty() || !FRICTAL_GWYDDION_ENABLED ? e : fmt::format("{}; install the {}", e, kPackages);
  return e.empty();
}

std::vector<FormatInfo> gwyddion_formats(const std::string& module_dir) {
  std::vector<FormatInfo> out;
  Backend& b = backend();
  std::lock_guard lock(b.mutex);
  if (!ensure_modules(b, module_root(module_dir)).empty()) return out;
  std::pair<Backend*, std::vector<FormatInfo>*> ctx{&b, &out};
  b.api.gwy_file_func_foreach(
      [](void* name, void* data) {
        auto* c = static_cast<std::pair<Backend*, std::vector<FormatInfo>*>*>(data);
        const char* n = static_cast<const char*>(name);
        const int ops = c->first->api.gwy_file_func_get_operations(n);
        if (!(ops & kOpLoad)) return;
        FormatInfo f;
        f.name = n;
        const char* d = c->first->api.gwy_file_func_get_description(n);
        f.description = d ? d : "";
        f.reader = "gwyddion";
        f.can_write = (ops & (kOpSave | kOpExport)) != 0;
        c->second->push_back(f);
      },
      &ctx);
  std::sort(out.begin(), out.end(), [](const FormatInfo& x, const FormatInfo& y) { return x.name < y.name; });
  return out;
}

namespace io_detail {

bool gwyddion_detects(const std::string& path, const std::string& module_dir) {
  Backend& b = backend();
  std::lock_guard lock(b.mutex);
  if (!ensure_modules(b, module_root(module_dir)).empty()) return false;
  return b.api.gwy_file_detect(path.c_str(), 0, kOpLoad) != nullptr;
}

Result<SurfaceData> read_gwyddion(const std::string& path, const ReadOptions& options) {
  Backend& b = backend();
  std::lock_guard lock(b.mutex);
  if (std::string e = ensure_modules(b, module_root(options.gwyddion_module_dir)); !e.empty())
    return make_error(fmt::format("{}: not a format frictal reads natively, and {}{}{}", path, e,
                                  FRICTAL_GWYDDION_ENABLED ? "; install the " : "",
                                  FRICTAL_GWYDDION_ENABLED ? kPackages : ""));
  const Api& a = b.api;
  const char* detected = a.gwy_file_detect(path.c_str(), 0, kOpLoad);
  if (!detected)
    return make_error(
        fmt::format("{}: neither frictal's readers nor any of Gwyddion's file modules recognise this file "
                    "(see `frictal formats`)",
                    path));
  GError* err = nullptr;
  const char* module = nullptr;
  LogCapture log(a);
  void* c = a.gwy_file_load_with_func(path.c_str(), kRunNonInteractive, &module, &err);
  std::vector<std::string> logged = log.take();
  if (!c) {
    std::string why = err && err->message ? err->message : "unknown error";
    for (const auto& m : logged) why += fmt::format(" ({})", m);
    if (err) a.g_error_free(err);
    return make_error(fmt::format("{}: Gwyddion's {} module could not load it: {}", path, detected, why));
  }
  if (err) a.g_error_free(err);
  struct Unref {
    const Api& a;
    void* c;
    ~Unref() { a.g_object_unref(c); }
  } guard{a, c};

  SurfaceData out;
  out.format = ProfileFormat::GwyddionLib;
  out.reader = fmt::format("gwyddion:{}", module ? module : detected);
  for (const auto& m : logged) out.warnings.emplace_back("reader", fmt::format("{}: {}", path, m));
  std::vector<Channel> chans = list_channels(a, c);
  for (const auto& ch : chans) out.channels.push_back(ch.info);
  if (chans.empty())
    return make_error(fmt::format("{}: Gwyddion's {} module found no image or graph in it", path, out.reader));
  // Which channel: --channel N (index in this list) or NAME (case-insensitive), else the first
  // image with lengths, else the first curve with lengths.
  std::size_t pick = chans.size();
  if (!options.channel.empty()) {
    long long n;
    if (parse_int64(options.channel, n)) {
      if (n < 0 || std::size_t(n) >= chans.size())
        return make_error(fmt::format("{}: channel {} requested but the file has {} (0..{}; see `frictal info`)", path,
                                      n, chans.size(), chans.size() - 1));
      pick = std::size_t(n);
    } else {
      for (std::size_t k = 0; k < chans.size() && pick == chans.size(); ++k)
        if (lower_ascii(chans[k].info.name) == lower_ascii(options.channel)) pick = k;
      if (pick == chans.size())
        return make_error(
            fmt::format("{}: no channel named '{}' (see `frictal info` for the list)", path, options.channel));
    }
  } else {
    auto lengths = [&](const Channel& c) { return length_scale(c.info.xy_unit) && length_scale(c.info.z_unit); };
    for (std::size_t k = 0; k < chans.size() && pick == chans.size(); ++k)
      if (chans[k].info.readable && lengths(chans[k]) && chans[k].info.is_map) pick = k;
    for (std::size_t k = 0; k < chans.size() && pick == chans.size(); ++k)
      if (chans[k].info.readable && lengths(chans[k])) pick = k;
    for (std::size_t k = 0; k < chans.size() && pick == chans.size(); ++k)
      if (chans[k].info.readable) pick = k;  // a channel without any unit
    if (pick == chans.size())
      return make_error(
          fmt::format("{}: no channel has heights and lateral sizes in a length unit (first: '{}' in {}, {}); "
                      "see `frictal info`",
                      path, chans[0].info.name, chans[0].info.xy_unit, chans[0].info.z_unit));
  }
  const Channel& ch = chans[pick];
  out.channel = pick;
  auto sxy = length_scale(ch.info.xy_unit), sz = length_scale(ch.info.z_unit);
  if (ch.info.is_map && ch.info.xy_unit.empty() && ch.info.z_unit.empty()) {
    std::optional<double> fallback = 1.0;
    if (!options.default_unit.empty()) fallback = length_scale(options.default_unit);
    if (!fallback) return make_error(fmt::format("unknown unit '{}' (expected m, mm, um, nm)", options.default_unit));
    sxy = sz = fallback;
    if (options.default_unit.empty())
      out.warnings.emplace_back(
          "reader",
          fmt::format("{}: channel '{}' carries no units; sizes and heights read as metres (give a unit to override)",
                      path, ch.info.name));
  }
  if (!sxy || !sz)
    return make_error(fmt::format("{}: channel {} '{}' has lateral unit '{}' and value unit '{}', not lengths", path,
                                  pick, ch.info.name, ch.info.xy_unit, ch.info.z_unit));
  out.x_unit_scale = *sxy;
  out.z_unit_scale = *sz;
  io_detail::InvalidCount invalid;
  if (ch.info.is_map) {
    void* f = nullptr;
    a.gwy_container_gis_object(c, a.g_quark_from_string(fmt::format("/{}/data", ch.id).c_str()), &f);
    const std::size_t nx = ch.info.nx, ny = ch.info.ny;
    if (nx == 0 || ny == 0 || nx > options.max_points / ny)
      return make_error(fmt::format("{}: {} x {} points exceed the limit of {}", path, nx, ny, options.max_points));
    Map& m = out.map;
    m.nx = nx;
    m.ny = ny;
    // Gwyddion's pixel convention: real size = n x spacing; offsets are the left/top edges.
    m.dx = a.gwy_data_field_get_xreal(f) * *sxy / double(nx);
    m.dy = a.gwy_data_field_get_yreal(f) * *sxy / double(ny);
    m.x0 = a.gwy_data_field_get_xoffset(f) * *sxy;
    m.y0 = a.gwy_data_field_get_yoffset(f) * *sxy;
    const double* d = a.gwy_data_field_get_data_const(f);
    m.heights.assign(d, d + nx * ny);
    io_detail::mask_invalid(m.heights, invalid);
    for (double& v : m.heights) v *= *sz;
    // The mask: Gwyddion's file modules mark invalid (unmeasured) points in /N/mask (> 0.5).
    void* mask = nullptr;
    if (a.gwy_container_gis_object(c, a.g_quark_from_string(fmt::format("/{}/mask", ch.id).c_str()), &mask) && mask &&
        a.g_type_check_instance_is_a(mask, a.gwy_data_field_get_type()) &&
        std::size_t(a.gwy_data_field_get_xres(mask)) == nx && std::size_t(a.gwy_data_field_get_yres(mask)) == ny) {
      const double* md = a.gwy_data_field_get_data_const(mask);
      for (std::size_t k = 0; k < nx * ny; ++k)
        if (md[k] > 0.5) m.heights[k] = std::numeric_limits<double>::quiet_NaN();
    }
    if (invalid.total()) out.warnings.emplace_back("reader", io_detail::invalid_warning(path, invalid, true));
    if (m.valid_count() == 0) return make_error(fmt::format("{}: channel '{}' has no valid point", path, ch.info.name));
    if (!(m.dx > 0) || !(m.dy > 0))
      return make_error(fmt::format("{}: channel '{}' has a zero or negative size", path, ch.info.name));
    out.is_map = true;
  } else {
    void* cm = a.gwy_graph_model_get_curve(ch.graph, ch.curve);
    const std::size_t n = std::size_t(a.gwy_graph_curve_model_get_ndata(cm));
    if (n > options.max_points)
      return make_error(fmt::format("{}: {} points exceed the limit of {}", path, n, options.max_points));
    const double* x = a.gwy_graph_curve_model_get_xdata(cm);
    const double* y = a.gwy_graph_curve_model_get_ydata(cm);
    for (std::size_t k = 0; k < n; ++k) {
      if (!std::isfinite(x[k]))
        return make_error(fmt::format("{}: curve '{}' point {} has x = {}", path, ch.info.name, k + 1, x[k]));
      if (!std::isfinite(y[k])) {
        invalid.add(y[k]);
        continue;
      }
      out.curve.x.push_back(x[k] * *sxy);
      out.curve.z.push_back(y[k] * *sz);
    }
    if (invalid.total()) out.warnings.emplace_back("reader", io_detail::invalid_warning(path, invalid, false));
    if (out.curve.size() < 2)
      return make_error(fmt::format("{}: curve '{}' has fewer than 2 valid points", path, ch.info.name));
  }
  return out;
}

}  // namespace io_detail

Status write_gwyddion(const std::string& path, const Map& m, const std::string& module_dir) {
  if (auto s = validate(m, path); !s) return s;
  static const char* const kTested[] = {".gwy", ".gsf",  ".sdf", ".sur", ".asc",
                                        ".ibw", ".nrrd", ".tom", ".afm", ".spm"};
  std::string ext =
      path.substr(std::min(path.size(), path.rfind('.') == std::string::npos ? path.size() : path.rfind('.')));
  ext = io_detail::lower_ascii(ext);
  if (std::find_if(std::begin(kTested), std::end(kTested), [&](const char* e) { return ext == e; }) ==
      std::end(kTested))
    return make_error(
        fmt::format("{}: writing '{}' through Gwyddion is not supported (tested: .gwy, .gsf, .sdf, .sur, .asc, "
                    ".ibw, .nrrd, .tom, .afm, .spm)",
                    path, ext));
  Backend& b = backend();
  std::lock_guard lock(b.mutex);
  if (std::string e = ensure_modules(b, module_root(module_dir)); !e.empty())
    return make_error(fmt::format("{}: cannot write through Gwyddion: {}{}{}", path, e,
                                  FRICTAL_GWYDDION_ENABLED ? "; install the " : "",
                                  FRICTAL_GWYDDION_ENABLED ? kPackages : ""));
  const Api& a = b.api;
  void* c = a.gwy_container_new();
  void* f = a.gwy_data_field_new(int(m.nx), int(m.ny), m.dx * double(m.nx), m.dy * double(m.ny), 1);
  a.gwy_data_field_set_xoffset(f, m.x0);
  a.gwy_data_field_set_yoffset(f, m.y0);
  void* u1 = a.gwy_si_unit_new("m");
  void* u2 = a.gwy_si_unit_new("m");
  a.gwy_data_field_set_si_unit_xy(f, u1);
  a.gwy_data_field_set_si_unit_z(f, u2);
  a.g_object_unref(u1);
  a.g_object_unref(u2);
  double* d = a.gwy_data_field_get_data(f);
  double mean = 0;
  std::size_t valid = 0;
  for (double v : m.heights)
    if (!std::isnan(v)) mean += v, ++valid;
  mean /= double(valid);
  void* mask = nullptr;
  for (std::size_t k = 0; k < m.size(); ++k) {
    d[k] = std::isnan(m.heights[k]) ? mean : m.heights[k];
    if (std::isnan(m.heights[k])) {
      if (!mask) mask = a.gwy_data_field_new(int(m.nx), int(m.ny), m.dx * double(m.nx), m.dy * double(m.ny), 1);
      a.gwy_data_field_get_data(mask)[k] = 1;
    }
  }
  a.gwy_container_set_object(c, a.g_quark_from_string("/0/data"), f);
  a.gwy_container_set_const_string(c, a.g_quark_from_string("/0/data/title"),
                                   reinterpret_cast<const unsigned char*>("Height"));
  a.g_object_unref(f);
  if (mask) {
    a.gwy_container_set_object(c, a.g_quark_from_string("/0/mask"), mask);
    a.g_object_unref(mask);
  }
  // Export modules write the data browser's current channel: register the container headless.
  a.gwy_app_data_browser_add(c);
  a.gwy_app_data_browser_select_data_field(c, 0);
  GError* err = nullptr;
  const char* module = nullptr;
  LogCapture log(a);
  int ops = a.gwy_file_save_with_func(c, path.c_str(), kRunNonInteractive, &module, &err);
  std::string why = err && err->message ? err->message : "";
  for (const auto& m : log.take()) why += fmt::format("{}({})", why.empty() ? "" : " ", m);
  if (err) a.g_error_free(err);
  a.gwy_app_data_browser_remove(c);
  a.g_object_unref(c);
  if (!ops)
    return make_error(
        fmt::format("{}: Gwyddion could not write it: {}", path, why.empty() ? "no module saves this type" : why));
  return Ok{};
}

}  // namespace frictal
