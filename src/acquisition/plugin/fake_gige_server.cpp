// FakeGigEServer: Aravis's GigE Vision fake camera (ArvGvFakeCamera) serving our images.
//
// The fake runs its own thread: it answers GVCP control requests and, when triggered, asks its
// fill-pattern callback for the frame, then streams it as GVSP packets. Our callback copies the
// image last given to serve(), so the whole GigE Vision path carries our pixels.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <mutex>
#include <thread>

#include "aravis_support.hpp"
#include "binpick/core/component_logger.hpp"
#include "fake_gige_fill.hpp"
#include "fake_gige_server.hpp"

namespace binpick::acquisition::detail {

namespace {

// How long suspend() lets the client's heartbeat (Aravis: one read of the control privilege per
// second) see the revoked privilege before the fake stops answering altogether. Without it the
// client would only notice after Aravis's read retries run out, about five seconds later.
constexpr auto kHeartbeatGrace = std::chrono::milliseconds(1300);

// The fake checks for a software trigger at this rate (its default, 25 Hz, adds up to 40 ms to
// every frame).
constexpr double kTriggerPollHz = 1000.0;

void requireFakeParams(const FakeCameraParams& p) {
  const std::string owner = "fake camera params";
  core::requireField(!p.address.empty(), owner, "address", "an interface address or name", p.address);
  core::requireField(!p.serial.empty() && p.serial.size() < 32, owner, "serial", "1 to 31 characters", p.serial);
  core::requireField(p.width > 0 && p.width <= 8192, owner, "width", "in [1, 8192]", p.width);
  core::requireField(p.height > 0 && p.height <= 8192, owner, "height", "in [1, 8192]", p.height);
}

// Aravis 0.8.26's fake only logs a warning when its GVCP port is taken and still reports itself
// running (answering nothing), so the port is tried here first. An interface given by name is
// left to the fake.
void requirePortFree(const std::string& address) {
  sockaddr_in socket_address{};
  socket_address.sin_family = AF_INET;
  socket_address.sin_port = htons(3956);
  if (inet_pton(AF_INET, address.c_str(), &socket_address.sin_addr) != 1) return;
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) return;
  const int result = bind(fd, reinterpret_cast<const sockaddr*>(&socket_address), sizeof(socket_address));
  const int bind_errno = errno;
  ::close(fd);
  if (result != 0 && bind_errno == EADDRINUSE) {
    throw core::Error("fake GigE camera: UDP port 3956 on " + address +
                      " is taken (another fake camera or GigE Vision tool is running)");
  }
}

}  // namespace

struct FakeGigEServer::State {
  FakeCameraParams params;
  ServedImage served;                  // read by Aravis's thread through the fill callback
  std::mutex control;                  // server lifetime and fault switches
  GObjectPtr<ArvGvFakeCamera> server;  // null while suspended
  double packet_loss = 0.0;

  void startServer();
};

// A sensor exactly the size of the images: an empty ROI on the client side ("the whole sensor")
// then asks for what we serve.
void FakeGigEServer::State::startServer() {
  requirePortFree(params.address);
  GObjectPtr<ArvGvFakeCamera> fake(arv_gv_fake_camera_new(params.address.c_str(), params.serial.c_str()));
  if (fake == nullptr || !arv_gv_fake_camera_is_running(fake.get())) {
    throw core::Error("fake GigE camera: cannot listen on '" + params.address +
                      "': no network interface with that address or name");
  }
  ArvFakeCamera* camera = arv_gv_fake_camera_get_fake_camera(fake.get());
  const auto width = static_cast<guint32>(params.width);
  const auto height = static_cast<guint32>(params.height);
  arv_fake_camera_write_register(camera, ARV_FAKE_CAMERA_REGISTER_SENSOR_WIDTH, width);
  arv_fake_camera_write_register(camera, ARV_FAKE_CAMERA_REGISTER_SENSOR_HEIGHT, height);
  arv_fake_camera_write_register(camera, ARV_FAKE_CAMERA_REGISTER_WIDTH, width);
  arv_fake_camera_write_register(camera, ARV_FAKE_CAMERA_REGISTER_HEIGHT, height);
  arv_fake_camera_write_register(camera, ARV_FAKE_CAMERA_REGISTER_PIXEL_FORMAT,
                                 params.sixteen_bit ? ARV_PIXEL_FORMAT_MONO_16 : ARV_PIXEL_FORMAT_MONO_8);
  arv_fake_camera_set_trigger_frequency(camera, kTriggerPollHz);
  arv_fake_camera_set_fill_pattern(camera, fillFromServedImage, &served);
  g_object_set(fake.get(), "gvsp-lost-ratio", packet_loss, nullptr);
  server = std::move(fake);
}

FakeGigEServer::FakeGigEServer(const FakeCameraParams& params) : state_(std::make_unique<State>()) {
  requireFakeParams(params);
  state_->params = params;
  state_->served.configure(params.width, params.height, params.sixteen_bit);
  state_->startServer();
}

// Unreffing the server joins its thread: no fill callback runs after this.
FakeGigEServer::~FakeGigEServer() = default;

void FakeGigEServer::serve(const cv::Mat& image) { state_->served.set(image); }

// Aravis's fake drops each stream packet (leader, payload, trailer) with this probability, using
// GLib's global random generator: seeding it makes the losses repeatable. The fake does not
// answer resend requests, so a lost packet means a lost frame.
void FakeGigEServer::setPacketLoss(double ratio, unsigned seed) {
  core::requireField(ratio >= 0.0 && ratio <= 1.0, "fake camera", "packet loss", "in [0, 1]", ratio);
  const std::lock_guard<std::mutex> lock(state_->control);
  state_->packet_loss = ratio;
  g_random_set_seed(seed);
  if (state_->server != nullptr) g_object_set(state_->server.get(), "gvsp-lost-ratio", ratio, nullptr);
}

// Aravis 0.8's fake has no switch to stop answering, so this revokes the client's control
// privilege (the fake stops streaming; the client's next heartbeat sees the privilege gone and
// emits control-lost), waits for that heartbeat, then shuts the server down: until resume(),
// requests go unanswered, as with an unplugged camera. Blocks for about 1.3 s.
void FakeGigEServer::suspend() {
  const std::lock_guard<std::mutex> lock(state_->control);
  if (state_->server == nullptr) return;
  arv_fake_camera_set_control_channel_privilege(arv_gv_fake_camera_get_fake_camera(state_->server.get()), 0);
  std::this_thread::sleep_for(kHeartbeatGrace);
  state_->server.reset();
  core::componentLogger("fake camera")
      ->info("fake camera {} at {}: suspended", state_->params.serial, state_->params.address);
}

// A fresh server, as after a power cycle: the client must open() again.
void FakeGigEServer::resume() {
  const std::lock_guard<std::mutex> lock(state_->control);
  if (state_->server != nullptr) return;
  state_->startServer();
  core::componentLogger("fake camera")
      ->info("fake camera {} at {}: resumed", state_->params.serial, state_->params.address);
}

}  // namespace binpick::acquisition::detail
