#pragma once
// Internal: ownership of GLib/Aravis objects and GError -> core::Error, shared by the Aravis
// camera and the fake GigE Vision camera. Aravis reports failures through GError out-parameters;
// here every one becomes a core::Error whose message says what we were doing and what Aravis
// said, and every GObject reference has exactly one owner that unrefs it.
#include <arv.h>

#include <memory>
#include <string>

#include "binpick/core/error.hpp"

namespace binpick::acquisition::detail {

struct GObjectUnref {
  void operator()(gpointer object) const {
    if (object != nullptr) g_object_unref(object);
  }
};
template <typename T>
using GObjectPtr = std::unique_ptr<T, GObjectUnref>;

// Collects one GError; throw_if_set() turns it into core::Error("CONTEXT: MESSAGE"), take()
// hands its message over for callers that report instead of throwing. Frees it either way.
class GErrorSlot {
 public:
  GErrorSlot() = default;
  GErrorSlot(const GErrorSlot&) = delete;
  GErrorSlot& operator=(const GErrorSlot&) = delete;
  ~GErrorSlot() { g_clear_error(&error_); }

  GError** out() {
    g_clear_error(&error_);
    return &error_;
  }
  bool isSet() const { return error_ != nullptr; }
  std::string take() {
    std::string message = error_ != nullptr && error_->message != nullptr ? error_->message : "unknown Aravis error";
    g_clear_error(&error_);
    return message;
  }
  void throwIfSet(const std::string& context) {
    if (error_ != nullptr) throw core::Error(context + ": " + take());
  }

 private:
  GError* error_ = nullptr;
};

}  // namespace binpick::acquisition::detail
