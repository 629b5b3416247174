// libmosquitto behind the BrokerClient: our own network thread rather than
// mosquitto_loop_start, because the library's loop gives up for good on
// some errors (a host name that does not resolve for a while, a refused
// password, a TLS failure) where a bridge in a lab must keep trying.

#include "broker_client.hpp"

#include <chrono>
#include <condition_variable>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <mosquitto.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <thread>

namespace aseba::mqtt
{

namespace
{

constexpr std::chrono::milliseconds RECONNECT_DELAY{ 1000 };
constexpr int LOOP_TIMEOUT_MS = 100;                         // how soon the thread sees a stop
constexpr std::chrono::milliseconds GOODBYE_LIMIT{ 1000 };   // to send the last words
constexpr std::chrono::milliseconds INBOX_FULL_WAIT{ 2000 }; // then a full inbox drops

std::once_flag library_initialised;

std::string error_text(int code)
{
    if (code == MOSQ_ERR_ERRNO)
        return std::strerror(errno);
    return mosquitto_strerror(code);
}

int parse_port(const std::string &text, const std::string &url)
{
    char *end = nullptr;
    long port = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || port < 1 || port > 65535)
        throw BrokerError("broker '" + url + "': the port must be a number from 1 to 65535");
    return int(port);
}

} // namespace

BrokerAddress parse_broker_url(const std::string &url)
{
    BrokerAddress address;
    std::string rest = url;
    size_t scheme_end = url.find("://");
    if (scheme_end != std::string::npos) {
        std::string scheme = url.substr(0, scheme_end);
        if (scheme == "mqtts")
            address.tls = true;
        else if (scheme != "mqtt")
            throw BrokerError("broker '" + url + "': the scheme must be mqtt:// or mqtts://");
        rest = url.substr(scheme_end + 3);
    }
    if (!rest.empty() && rest.back() == '/')
        rest.pop_back();
    address.port = address.tls ? DEFAULT_TLS_PORT : DEFAULT_PORT;
    size_t colon = rest.rfind(':');
    bool ipv6_bracket = !rest.empty() && rest.front() == '[';
    if (ipv6_bracket) {
        size_t close = rest.find(']');
        if (close == std::string::npos)
            throw BrokerError("broker '" + url + "': unclosed '[' in the host");
        address.host = rest.substr(1, close - 1);
        if (close + 1 < rest.size()) {
            if (rest[close + 1] != ':')
                throw BrokerError("broker '" + url + "': expected ':PORT' after the host");
            address.port = parse_port(rest.substr(close + 2), url);
        }
    } else if (colon != std::string::npos) {
        address.host = rest.substr(0, colon);
        address.port = parse_port(rest.substr(colon + 1), url);
    } else {
        address.host = rest;
    }
    if (address.host.empty() || address.host.find('/') != std::string::npos)
        throw BrokerError("broker '" + url + "': expected mqtt://HOST:PORT");
    return address;
}

// The network thread and its stop signal.
struct BrokerThread {
    std::mutex mutex;
    std::condition_variable stop_signal;
    bool stopping = false;
    std::thread thread;
};

namespace
{

// One thread per client: connect, loop, reconnect after a delay, until
// told to stop.
// Debian's mosquitto leaves Nagle's algorithm on (set_tcp_nodelay false):
// it holds a small PUBLISH until the previous segment is acknowledged, and
// Linux delays that acknowledgement by up to 40 ms, which made a robot's
// event take 20 ms from broker to bridge. Acknowledging at once keeps the
// broker's queue moving. The kernel clears TCP_QUICKACK again as it pleases,
// so it is set around every read.
void acknowledge_at_once(struct mosquitto *client)
{
    int socket = mosquitto_socket(client);
    int on = 1;
    if (socket >= 0)
        setsockopt(socket, IPPROTO_TCP, TCP_QUICKACK, &on, sizeof on);
}

void run_network(struct mosquitto *client,
                 const BrokerOptions &options,
                 BrokerThread &control,
                 const std::function<void(const std::string &)> &report_error)
{
    bool open = false;
    std::optional<std::chrono::steady_clock::time_point> stop_deadline;
    while (true) {
        {
            std::lock_guard lock(control.mutex);
            if (control.stopping && !stop_deadline)
                stop_deadline = std::chrono::steady_clock::now() + GOODBYE_LIMIT;
        }
        if (stop_deadline && (!open || std::chrono::steady_clock::now() > *stop_deadline))
            return;
        if (!open) {
            int code = mosquitto_connect(client,
                                         options.address.host.c_str(),
                                         options.address.port,
                                         options.keepalive_seconds);
            if (code == MOSQ_ERR_SUCCESS) {
                open = true;
                continue;
            }
            report_error("cannot connect: " + error_text(code));
            std::unique_lock lock(control.mutex);
            control.stop_signal.wait_for(lock, RECONNECT_DELAY, [&] { return control.stopping; });
            continue;
        }
        acknowledge_at_once(client);
        int code = mosquitto_loop(client, LOOP_TIMEOUT_MS, 1);
        acknowledge_at_once(client);
        if (code != MOSQ_ERR_SUCCESS) {
            open = false;
            if (code != MOSQ_ERR_NO_CONN || !stop_deadline)
                report_error("connection lost: " + error_text(code));
            std::unique_lock lock(control.mutex);
            control.stop_signal.wait_for(lock, RECONNECT_DELAY, [&] { return control.stopping; });
        }
    }
}

} // namespace

BrokerClient::BrokerClient(BrokerOptions options, std::function<void()> wake)
  : options_(std::move(options))
  , wake_(std::move(wake))
  , thread_(std::make_unique<BrokerThread>())
{
    std::call_once(library_initialised, [] { mosquitto_lib_init(); });
    // A persistent session (clean_session false): what the broker holds for
    // us while we are away is delivered when we come back.
    client_ = mosquitto_new(options_.client_id.c_str(), false, this);
    if (client_ == nullptr)
        throw BrokerError("cannot create an MQTT client (id '" + options_.client_id +
                          "'): " + std::strerror(errno));
    auto check = [this](int code, const std::string &what) {
        if (code != MOSQ_ERR_SUCCESS) {
            mosquitto_destroy(client_);
            throw BrokerError(what + ": " + error_text(code));
        }
    };
    check(mosquitto_threaded_set(client_, true), "threads");
    check(mosquitto_int_option(client_, MOSQ_OPT_PROTOCOL_VERSION, MQTT_PROTOCOL_V311),
          "protocol version");
    check(mosquitto_int_option(client_, MOSQ_OPT_TCP_NODELAY, 1), "TCP_NODELAY");
    if (!options_.username.empty())
        check(mosquitto_username_pw_set(client_,
                                        options_.username.c_str(),
                                        options_.password.empty() ? nullptr
                                                                  : options_.password.c_str()),
              "username");
    if (options_.address.tls) {
        auto optional_path = [](const std::string &path) {
            return path.empty() ? nullptr : path.c_str();
        };
        // Without a file or folder of authorities, the system's ones.
        const char *ca_path = options_.ca_file.empty() && options_.ca_path.empty()
                                ? "/etc/ssl/certs"
                                : optional_path(options_.ca_path);
        check(mosquitto_tls_set(client_,
                                optional_path(options_.ca_file),
                                ca_path,
                                optional_path(options_.cert_file),
                                optional_path(options_.key_file),
                                nullptr),
              "TLS");
    }
    if (!options_.will_topic.empty())
        check(mosquitto_will_set(client_,
                                 options_.will_topic.c_str(),
                                 int(options_.will_payload.size()),
                                 options_.will_payload.data(),
                                 1,
                                 true),
              "last will");
    mosquitto_connect_callback_set(client_, on_connect);
    mosquitto_disconnect_callback_set(client_, on_disconnect);
    mosquitto_message_callback_set(client_, on_message);
    thread_->thread = std::thread([this] {
        run_network(
          client_, options_, *thread_, [this](const std::string &error) { set_error(error); });
    });
}

BrokerClient::~BrokerClient()
{
    if (connected_ && !options_.will_topic.empty() && !options_.goodbye_payload.empty())
        publish_now(options_.will_topic, options_.goodbye_payload, 1, true);
    mosquitto_disconnect(client_);
    {
        std::lock_guard lock(thread_->mutex);
        thread_->stopping = true;
    }
    thread_->stop_signal.notify_all();
    thread_->thread.join();
    mosquitto_destroy(client_);
}

void BrokerClient::subscribe(std::vector<std::string> filters, int qos)
{
    {
        std::lock_guard lock(mutex_);
        filters_ = filters;
        filters_qos_ = qos;
    }
    if (connected_)
        for (const std::string &filter : filters)
            mosquitto_subscribe(client_, nullptr, filter.c_str(), qos);
}

std::string BrokerClient::last_error() const
{
    std::lock_guard lock(mutex_);
    return last_error_;
}

void BrokerClient::set_error(const std::string &error)
{
    {
        std::lock_guard lock(mutex_);
        last_error_ = error;
    }
    wake_();
}

bool BrokerClient::publish_now(const std::string &topic,
                               const std::string &payload,
                               int qos,
                               bool retain)
{
    int code = mosquitto_publish(
      client_, nullptr, topic.c_str(), int(payload.size()), payload.data(), qos, retain);
    return code == MOSQ_ERR_SUCCESS;
}

bool BrokerClient::publish(const std::string &topic,
                           const std::string &payload,
                           int qos,
                           bool retain)
{
    // Behind older publications still waiting, so that the order holds.
    if (connected_ && pending_.empty() && publish_now(topic, payload, qos, retain))
        return true;
    if (qos == 0)
        return false;
    if (pending_.size() >= options_.pending_limit) {
        std::lock_guard lock(mutex_);
        ++drops_.pending_full;
        return false;
    }
    pending_.push_back(Publication{ topic, payload, qos, retain });
    return true;
}

void BrokerClient::flush_pending()
{
    while (connected_ && !pending_.empty()) {
        const Publication &next = pending_.front();
        if (!publish_now(next.topic, next.payload, next.qos, next.retain))
            return;
        pending_.pop_front();
    }
}

std::vector<InboundMessage> BrokerClient::take_messages()
{
    std::vector<InboundMessage> messages;
    {
        std::lock_guard lock(mutex_);
        messages.swap(inbox_);
    }
    inbox_space_.notify_all();
    return messages;
}

BrokerDrops BrokerClient::drops() const
{
    std::lock_guard lock(mutex_);
    return drops_;
}

void BrokerClient::on_connect(struct mosquitto *client, void *self_pointer, int code)
{
    auto &self = *static_cast<BrokerClient *>(self_pointer);
    if (code != 0) {
        self.set_error(std::string("the broker refused the connection: ") +
                       mosquitto_connack_string(code));
        return;
    }
    std::vector<std::string> filters;
    int qos = 1;
    {
        std::lock_guard lock(self.mutex_);
        filters = self.filters_;
        qos = self.filters_qos_;
        self.last_error_.clear();
    }
    for (const std::string &filter : filters)
        mosquitto_subscribe(client, nullptr, filter.c_str(), qos);
    self.connected_ = true;
    ++self.connections_;
    self.wake_();
}

void BrokerClient::on_disconnect(struct mosquitto *, void *self_pointer, int)
{
    auto &self = *static_cast<BrokerClient *>(self_pointer);
    self.connected_ = false;
    self.wake_();
}

void BrokerClient::on_message(struct mosquitto *,
                              void *self_pointer,
                              const struct mosquitto_message *message)
{
    auto &self = *static_cast<BrokerClient *>(self_pointer);
    {
        std::unique_lock lock(self.mutex_);
        if (size_t(message->payloadlen) > self.options_.payload_limit) {
            ++self.drops_.oversized;
            return;
        }
        // A full inbox first holds libmosquitto's thread back for a while,
        // so that the broker keeps what it sends (TCP slows it down) while
        // the owner is merely late; only a sender that outlasts that wait
        // loses messages.
        if (self.inbox_.size() >= self.options_.inbox_limit)
            self.inbox_space_.wait_for(lock, INBOX_FULL_WAIT, [&] {
                return self.inbox_.size() < self.options_.inbox_limit;
            });
        if (self.inbox_.size() >= self.options_.inbox_limit) {
            ++self.drops_.inbox_full;
            return;
        }
        self.inbox_.push_back(InboundMessage{
          message->topic,
          std::string(static_cast<const char *>(message->payload), size_t(message->payloadlen)) });
    }
    self.wake_();
}

} // namespace aseba::mqtt
