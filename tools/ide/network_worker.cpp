// The network thread: poll, run tasks, read watched variables, report.

#include "network_worker.hpp"

#include <algorithm>
#include <iostream>

#include <asio/post.hpp>

namespace aseba::ide
{

namespace
{

// How long one poll may wait for bytes: the delay before a queued task runs.
constexpr client::Milliseconds POLL_PERIOD{ 10 };
// How often a robot whose execution state is unknown is asked for it.
constexpr client::Milliseconds STATE_QUESTION_PERIOD{ 1000 };

// What the IDE shows of a node, as text, to tell when it changed.
std::string robot_signature(const client::Node &node, bool alive)
{
    std::string signature = std::to_string(node.described) + std::to_string(node.compatible) +
                            std::to_string(alive) + ":" + std::to_string(node.protocol_version);
    if (node.execution)
        signature +=
          ":" + std::to_string(node.execution->pc) + "/" + std::to_string(node.execution->flags);
    return signature;
}

// A link's failure without the target it starts with: the target is
// shown beside it.
std::string without_target(const std::string &reason, const std::string &target)
{
    std::string prefix = target + ": ";
    return reason.starts_with(prefix) ? reason.substr(prefix.size()) : reason;
}

} // namespace

NetworkWorker::NetworkWorker(asio::io_context &reports_context,
                             std::vector<std::string> targets,
                             NetworkReports reports,
                             client::Milliseconds answer_timeout)
  : reports_context_(reports_context)
  , targets_(std::move(targets))
  , reports_(std::make_shared<const NetworkReports>(std::move(reports)))
  , answer_timeout_(answer_timeout)
  , network_(std::make_unique<client::Network>(answer_timeout))
{
    network_->set_listener([this](const client::ReceivedFrame &frame) { heard_.push_back(frame); });
    network_->set_link_listener(
      [this](size_t target, client::LinkState state, const std::string &reason) {
          links_.at(target).up = state == client::LinkState::up;
          links_.at(target).error = without_target(reason, network_->target_name(target));
      });
    // Targets that cannot be reached now are tried again by the Network;
    // only a malformed target string throws, before the thread starts.
    for (const std::string &target : targets_) {
        size_t index = network_->connect(target, client::LinkPolicy::reconnect);
        links_.push_back(
          LinkStatus{ target,
                      network_->link_state(index) == client::LinkState::up,
                      without_target(network_->link_error(index), network_->target_name(index)) });
    }
    thread_ = std::thread([this] { run(); });
}

NetworkWorker::~NetworkWorker()
{
    {
        std::lock_guard lock(mutex_);
        stopping_ = true;
    }
    network_->wake();
    thread_.join();
    network_.reset();
}

void NetworkWorker::submit(NetworkTask task)
{
    {
        std::lock_guard lock(mutex_);
        tasks_.push_back(std::move(task));
    }
    network_->wake();
}

void NetworkWorker::watch(std::map<NodeKey, uint16_t> words)
{
    std::lock_guard lock(mutex_);
    watched_ = std::move(words);
}

template<typename Function>
void NetworkWorker::report(Function &&function)
{
    asio::post(reports_context_,
               [reports = reports_, function = std::forward<Function>(function)]() mutable {
                   function(*reports);
               });
}

void NetworkWorker::run()
{
    report_links();
    while (true) {
        {
            std::lock_guard lock(mutex_);
            if (stopping_)
                break;
        }
        try {
            // Until the next variables are due, or a task or a frame comes.
            auto until_variables =
              std::chrono::ceil<client::Milliseconds>(next_variables_read_ - client::Clock::now());
            network_->poll(std::clamp(
              until_variables, client::Milliseconds(1), client::Milliseconds(VARIABLES_PERIOD)));
            network_->keep_alive();
            run_tasks();
            refresh_variables();
        } catch (const std::exception &error) {
            // A broken frame or a link that failed in a task: the Network has
            // marked what it must; the reports below say the rest.
            std::cerr << "aseba-ide: " << error.what() << "\n";
        }
        report_links();
        report_robots();
        if (!heard_.empty())
            report([frames = std::move(heard_)](const NetworkReports &reports) mutable {
                reports.frames(std::move(frames));
            });
        heard_.clear();
    }
    // Tasks still queued learn that no answer will come.
    serving_ = false;
    run_tasks();
}

void NetworkWorker::run_tasks()
{
    while (true) {
        NetworkTask task;
        {
            std::lock_guard lock(mutex_);
            if (tasks_.empty())
                return;
            task = std::move(tasks_.front());
            tasks_.pop_front();
        }
        task(serving_ ? network_.get() : nullptr);
    }
}

void NetworkWorker::refresh_variables()
{
    auto now = client::Clock::now();
    if (now < next_variables_read_)
        return;
    next_variables_read_ = now + VARIABLES_PERIOD;
    std::map<NodeKey, uint16_t> watched;
    {
        std::lock_guard lock(mutex_);
        watched = watched_;
    }
    for (const auto &[key, words] : watched) {
        std::vector<NodeKey> keys = network_->node_keys();
        if (std::find(keys.begin(), keys.end(), key) == keys.end())
            continue;
        const client::Node &node = network_->node(key);
        if (!node.described || !node.compatible || !network_->is_alive(key))
            continue;
        uint16_t length = std::min(words, node.description.variables_size);
        if (length == 0)
            continue;
        try {
            std::vector<int16_t> values = network_->read_variables(key, 0, length);
            report([key = key, values = std::move(values)](const NetworkReports &reports) mutable {
                reports.variables(key, std::move(values));
            });
        } catch (const client::TimeoutError &) {
            // A robot that does not answer shows its last values; its
            // silence shows in its state.
        } catch (const client::NetworkError &) {
        }
    }
}

void NetworkWorker::report_robots()
{
    std::vector<NodeKey> keys = network_->node_keys();
    for (NodeKey key : keys) {
        const client::Node &node = network_->node(key);
        bool alive = network_->is_alive(key);
        // A robot running since before we came, or rebooted, says how it
        // runs only when asked, again until it answers (a rebooting robot
        // does not hear); its answer updates the model like any other.
        if (node.described && node.compatible && !node.execution && alive) {
            auto now = client::Clock::now();
            auto [asked, first] = state_asked_.try_emplace(key, now);
            if (first || now - asked->second >= STATE_QUESTION_PERIOD) {
                asked->second = now;
                network_->send(key.target,
                               client::NodeCommand{ NODE_MSG_GET_EXECUTION_STATE, key.id });
            }
        } else {
            state_asked_.erase(key);
        }
        std::string signature = robot_signature(node, alive);
        auto [entry, is_new] = reported_robots_.try_emplace(key, signature);
        if (!is_new && entry->second == signature)
            continue;
        entry->second = signature;
        RobotSnapshot snapshot{ key,
                                node.described,
                                node.compatible,
                                alive,
                                node.protocol_version,
                                node.described ? node.description : TargetDescription{},
                                node.execution };
        report([snapshot = std::move(snapshot)](const NetworkReports &reports) mutable {
            reports.robot_changed(std::move(snapshot));
        });
    }
    for (auto entry = reported_robots_.begin(); entry != reported_robots_.end();) {
        if (std::find(keys.begin(), keys.end(), entry->first) == keys.end()) {
            report(
              [key = entry->first](const NetworkReports &reports) { reports.robot_gone(key); });
            state_asked_.erase(entry->first);
            entry = reported_robots_.erase(entry);
        } else {
            ++entry;
        }
    }
}

void NetworkWorker::report_links()
{
    std::string summary;
    for (const LinkStatus &link : links_)
        summary += link.target + (link.up ? " up" : " down: " + link.error) + "\n";
    if (summary == links_reported_)
        return;
    links_reported_ = summary;
    report([links = links_](const NetworkReports &reports) mutable {
        reports.links_changed(std::move(links));
    });
}

} // namespace aseba::ide
