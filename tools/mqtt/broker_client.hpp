// The bridge's connection to an MQTT broker, over libmosquitto (Debian's
// libmosquitto-dev) with the library's own network thread. It connects in
// the background and reconnects by itself; it subscribes again after every
// connection; what arrives waits in a bounded inbox for the owner's thread;
// what is published at QoS 1 while the broker is away waits in a bounded
// queue and goes out, in order, at the next connection.
//
// One thread owns a BrokerClient; the callbacks of libmosquitto's thread only
// fill the inbox, count, and call `wake` so that the owner looks.

#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

struct mosquitto;
struct mosquitto_message;

namespace aseba::mqtt
{
struct BrokerThread;
}

namespace aseba::mqtt
{

// A broker address or option the bridge cannot use.
class BrokerError : public std::runtime_error
{
  public:
    using std::runtime_error::runtime_error;
};

constexpr int DEFAULT_PORT = 1883;
constexpr int DEFAULT_TLS_PORT = 8883;

struct BrokerAddress {
    bool tls = false;
    std::string host = "localhost";
    int port = DEFAULT_PORT;
};

// Parses `mqtt://HOST[:PORT]` or `mqtts://HOST[:PORT]` (TLS, port 8883 by
// default); a bare `HOST[:PORT]` means mqtt://. Throws BrokerError.
BrokerAddress parse_broker_url(const std::string &url);

struct BrokerOptions {
    BrokerAddress address;
    std::string client_id; // fixed, so that the broker keeps the session
    std::string username;  // empty: none
    std::string password;
    std::string ca_file;   // TLS: the authority that signed the broker's certificate
    std::string ca_path;   // TLS: a folder of authorities (default: the system's)
    std::string cert_file; // TLS: this client's certificate and key, if the broker asks
    std::string key_file;
    int keepalive_seconds = 10;
    // Published by the broker for us when we vanish without saying goodbye.
    std::string will_topic;
    std::string will_payload;
    // Sent by us on a clean stop, on will_topic, retained.
    std::string goodbye_payload;
    size_t inbox_limit = 1000;         // messages waiting for the owner
    size_t payload_limit = 256 * 1024; // bytes; larger messages are dropped
    size_t pending_limit = 10000;      // QoS 1 publications waiting for the broker
};

struct InboundMessage {
    std::string topic;
    std::string payload;
};

// What the broker side dropped so far, for the owner's log.
struct BrokerDrops {
    uint64_t inbox_full = 0;   // arrived while the inbox was full
    uint64_t oversized = 0;    // larger than payload_limit
    uint64_t pending_full = 0; // published while the pending queue was full
};

class BrokerClient
{
  public:
    // Starts connecting (never throws for an unreachable broker: it is
    // tried again every second or two); throws BrokerError for options
    // libmosquitto refuses (a TLS file that cannot be read, ...).
    BrokerClient(BrokerOptions options, std::function<void()> wake);
    // Publishes the goodbye (if any), disconnects and stops the thread.
    ~BrokerClient();
    BrokerClient(const BrokerClient &) = delete;
    BrokerClient &operator=(const BrokerClient &) = delete;

    // The topic filters to subscribe to, now and after every connection.
    void subscribe(std::vector<std::string> filters, int qos);

    bool connected() const
    {
        return connected_;
    }
    // Grows by one at each successful connection: the owner compares it to
    // know when to publish its retained state again.
    uint64_t connections() const
    {
        return connections_;
    }
    // Why the last connection attempt failed or the connection was lost.
    std::string last_error() const;

    // Publishes; at QoS 1 a message the broker cannot take now waits (in a
    // queue of pending_limit, beyond which it is dropped and counted); at
    // QoS 0 it is dropped when not connected. Returns false when dropped.
    bool publish(const std::string &topic, const std::string &payload, int qos, bool retain);

    // Sends what waited for the broker, in order; call after a connection.
    void flush_pending();
    size_t pending() const
    {
        return pending_.size();
    }

    // The messages received since the last call, oldest first.
    std::vector<InboundMessage> take_messages();

    BrokerDrops drops() const;

  private:
    static void on_connect(struct mosquitto *, void *self, int code);
    static void on_disconnect(struct mosquitto *, void *self, int code);
    static void on_message(struct mosquitto *, void *self, const struct mosquitto_message *message);
    void set_error(const std::string &error);
    // Publishes now; false if libmosquitto refuses (not connected).
    bool publish_now(const std::string &topic, const std::string &payload, int qos, bool retain);

    struct Publication {
        std::string topic;
        std::string payload;
        int qos;
        bool retain;
    };

    BrokerOptions options_;
    std::function<void()> wake_;
    std::unique_ptr<BrokerThread> thread_;
    struct mosquitto *client_ = nullptr;
    std::atomic<bool> connected_{ false };
    std::atomic<uint64_t> connections_{ 0 };
    std::deque<Publication> pending_; // the owner's thread only

    mutable std::mutex mutex_; // what libmosquitto's thread shares with the owner
    std::vector<std::string> filters_;
    int filters_qos_ = 1;
    std::vector<InboundMessage> inbox_;
    std::condition_variable inbox_space_; // the owner took the inbox's messages
    std::string last_error_;
    BrokerDrops drops_;
};

} // namespace aseba::mqtt
