// The arena feed on standalone asio, polled from the simulation's loop.

#include "arena_feed.hpp"

#include <cmath>
#include <deque>
#include <list>
#include <stdexcept>

#include <asio/buffer.hpp>
#include <asio/io_context.hpp>
#include <asio/ip/tcp.hpp>
#include <asio/write.hpp>
#include <nlohmann/json.hpp>

namespace aseba::arena
{

namespace
{

using Json = nlohmann::json;
using asio::ip::tcp;

// A viewer with this much unsent misses updates until it reads again.
constexpr size_t MAX_QUEUED_BYTES = 256 * 1024;
// The e-puck's body, for drawing (cm).
constexpr double ROBOT_RADIUS = 3.7;
constexpr double DEGREES_PER_RADIAN = 180.0 / M_PI;

Json color_json(const Color &color)
{
    return Json::array({ color.red, color.green, color.blue });
}

} // namespace

std::string arena_geometry_json(const Arena &arena)
{
    Json areas = Json::array();
    for (const GroundArea &area : arena.areas) {
        Json json{ { "x", area.x },
                   { "y", area.y },
                   { "color", color_json(area.color) },
                   { "shock", area.shock_period } };
        if (area.shape == GroundArea::Shape::disc) {
            json["shape"] = "disc";
            json["radius"] = area.radius;
        } else {
            json["shape"] = "rectangle";
            json["width"] = area.width;
            json["height"] = area.height;
        }
        areas.push_back(json);
    }
    Json obstacles = Json::array();
    for (const Obstacle &obstacle : arena.obstacles) {
        Json json{ { "x", obstacle.x },
                   { "y", obstacle.y },
                   { "color", color_json(obstacle.color) } };
        if (obstacle.shape == Obstacle::Shape::cylinder) {
            json["shape"] = "cylinder";
            json["radius"] = obstacle.radius;
        } else {
            json["shape"] = "box";
            json["length"] = obstacle.length;
            json["width"] = obstacle.width;
            json["heading"] = obstacle.heading_degrees;
        }
        obstacles.push_back(json);
    }
    Json sounds = Json::array();
    for (const SoundSource &sound : arena.sounds)
        sounds.push_back({ { "x", sound.x },
                           { "y", sound.y },
                           { "frequency", sound.frequency },
                           { "level", sound.level } });
    Json geometry{ { "width", arena.width },
                   { "height", arena.height },
                   { "floor", color_json(arena.floor_color) },
                   { "walls", color_json(arena.wall_color) },
                   { "areas", areas },
                   { "obstacles", obstacles },
                   { "sounds", sounds },
                   { "robotRadius", ROBOT_RADIUS } };
    return Json{ { "type", "arena" }, { "arena", geometry } }.dump() + "\n";
}

struct ArenaFeed::Implementation {
    struct Viewer {
        tcp::socket socket;
        connections::Clock::time_point arrived;
        std::deque<std::string> queue; // the front one is being written
        size_t queued_bytes = 0;
        bool closed = false;
        unsigned pending = 0; // operations whose handler has not run: it holds &viewer
        char discard[256];

        void close()
        {
            closed = true;
            std::error_code ignored;
            // The queue stays: a write in flight still reads its buffer until
            // its handler runs.
            socket.close(ignored);
        }
    };

    asio::io_context io;
    tcp::acceptor acceptor{ io };
    connections::PortLimit limit;
    bool accepting = false;
    std::string geometry;
    std::list<Viewer> viewers;

    void accept()
    {
        accepting = true;
        acceptor.async_accept([this](const std::error_code &error, tcp::socket socket) {
            accepting = false;
            if (error)
                return; // tried again at the next service()
            if (make_room()) {
                std::error_code ignored;
                socket.set_option(tcp::no_delay(true), ignored);
                Viewer &viewer = viewers.emplace_back(
                  Viewer{ std::move(socket), connections::Clock::now(), {}, 0, false, 0, {} });
                send(viewer, geometry);
                read(viewer);
            }
            accept();
        });
    }

    // Whether a newcomer may watch: the feed has room, or its oldest viewer
    // has watched for the grace and leaves.
    bool make_room()
    {
        return connections::make_room(
          viewers,
          [](const Viewer &member) { return !member.closed; },
          [](const Viewer &member) { return member.arrived; },
          [](Viewer &member) { member.close(); },
          limit);
    }

    // Viewers have nothing to say; reading tells when they leave.
    void read(Viewer &viewer)
    {
        viewer.pending++;
        viewer.socket.async_read_some(asio::buffer(viewer.discard),
                                      [this, &viewer](const std::error_code &error, size_t) {
                                          viewer.pending--;
                                          if (error)
                                              viewer.close();
                                          else if (!viewer.closed)
                                              read(viewer);
                                      });
    }

    void send(Viewer &viewer, const std::string &line)
    {
        viewer.queue.push_back(line);
        viewer.queued_bytes += line.size();
        if (viewer.queue.size() == 1)
            write(viewer);
    }

    void write(Viewer &viewer)
    {
        viewer.pending++;
        asio::async_write(viewer.socket,
                          asio::buffer(viewer.queue.front()),
                          [this, &viewer](const std::error_code &error, size_t) {
                              viewer.pending--;
                              if (error || viewer.closed) {
                                  viewer.close();
                                  return;
                              }
                              viewer.queued_bytes -= viewer.queue.front().size();
                              viewer.queue.pop_front();
                              if (!viewer.queue.empty())
                                  write(viewer);
                          });
    }
};

ArenaFeed::ArenaFeed(const Arena &arena,
                     const std::string &address,
                     uint16_t port,
                     const connections::PortLimit &limit)
  : implementation_(std::make_unique<Implementation>())
{
    Implementation &self = *implementation_;
    self.limit = limit;
    self.geometry = arena_geometry_json(arena);
    std::error_code error;
    tcp::endpoint endpoint(asio::ip::make_address(address, error), port);
    if (!error)
        self.acceptor.open(endpoint.protocol(), error);
    if (!error)
        self.acceptor.set_option(tcp::acceptor::reuse_address(true), error);
    if (!error)
        self.acceptor.bind(endpoint, error);
    if (!error)
        self.acceptor.listen(asio::socket_base::max_listen_connections, error);
    if (error)
        throw std::runtime_error("cannot open the arena feed on " + address + " port " +
                                 std::to_string(port) + ": " + error.message());
    self.accept();
}

ArenaFeed::~ArenaFeed() = default;

uint16_t ArenaFeed::port() const
{
    return implementation_->acceptor.local_endpoint().port();
}

void ArenaFeed::publish(double simulated_seconds, const std::vector<FeedRobot> &robots)
{
    Implementation &self = *implementation_;
    if (self.viewers.empty())
        return;
    Json list = Json::array();
    for (const FeedRobot &robot : robots) {
        Json ring = Json::array();
        for (bool on : robot.ring)
            ring.push_back(on ? 1 : 0);
        // Rounded: a viewer draws pixels, not micrometres.
        list.push_back(
          { { "id", robot.node_id },
            { "x", std::round(robot.pose.x * 100) / 100 },
            { "y", std::round(robot.pose.y * 100) / 100 },
            { "heading", std::round(robot.pose.heading * DEGREES_PER_RADIAN * 10) / 10 },
            { "leds", ring },
            { "body", robot.body ? 1 : 0 },
            { "front", robot.front ? 1 : 0 } });
    }
    std::string line = Json{
        { "type", "state" },
        { "time", std::round(simulated_seconds * 1000) / 1000 },
        { "robots", list }
    }.dump() + "\n";
    for (Implementation::Viewer &viewer : self.viewers)
        if (!viewer.closed && viewer.queued_bytes < MAX_QUEUED_BYTES)
            self.send(viewer, line);
}

void ArenaFeed::service()
{
    Implementation &self = *implementation_;
    self.io.poll();
    self.io.restart();
    self.viewers.remove_if(
      [](const Implementation::Viewer &viewer) { return viewer.closed && viewer.pending == 0; });
    if (!self.accepting)
        self.accept();
}

size_t ArenaFeed::viewer_count() const
{
    return implementation_->viewers.size();
}

} // namespace aseba::arena
