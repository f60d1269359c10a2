//! `metadata.yaml`, the file `ros2 bag info` and `ros2 bag play` read beside the storage file:
//! version 5 of rosbag2's bag information (ROS 2 Humble reads versions up to 5; later
//! distributions read it too).

use std::fmt::Write;

/// One topic of a bag and how many messages it holds.
pub struct TopicCount {
    pub name: String,
    pub message_type: String,
    /// rosbag2's `offered_qos_profiles` text (YAML), empty for the subscriber's default.
    pub qos: String,
    pub messages: u64,
}

/// The YAML text, its fields in the order rosbag2 writes them.
pub fn metadata_yaml(file: &str, start_ns: u64, end_ns: u64, topics: &[TopicCount]) -> String {
    let messages: u64 = topics.iter().map(|t| t.messages).sum();
    let duration = end_ns.saturating_sub(start_ns);
    let mut y = String::from("rosbag2_bagfile_information:\n  version: 5\n");
    y.push_str("  storage_identifier: mcap\n");
    let _ = writeln!(y, "  duration:\n    nanoseconds: {duration}");
    let _ = writeln!(
        y,
        "  starting_time:\n    nanoseconds_since_epoch: {start_ns}"
    );
    let _ = writeln!(y, "  message_count: {messages}");
    y.push_str("  topics_with_message_count:\n");
    for topic in topics {
        let _ = write!(
            y,
            "    - topic_metadata:\n        name: {}\n        type: {}\n        \
             serialization_format: cdr\n        offered_qos_profiles: {}\n      \
             message_count: {}\n",
            topic.name,
            topic.message_type,
            quoted(&topic.qos),
            topic.messages
        );
    }
    y.push_str("  compression_format: \"\"\n  compression_mode: \"\"\n");
    let file = quoted(file);
    let _ = writeln!(y, "  relative_file_paths:\n    - {file}");
    let _ = write!(
        y,
        "  files:\n    - path: {file}\n      starting_time:\n        nanoseconds_since_epoch: \
         {start_ns}\n      duration:\n        nanoseconds: {duration}\n      message_count: \
         {messages}\n"
    );
    y
}

/// A YAML double-quoted scalar.
fn quoted(text: &str) -> String {
    format!(
        "\"{}\"",
        text.replace('\\', "\\\\")
            .replace('"', "\\\"")
            .replace('\n', "\\n")
    )
}

/// The QoS rosbag2 records for a latched topic such as `/tf_static`: reliable and transient
/// local, so that `ros2 bag play` hands it to subscribers that join late.
pub const LATCHED_QOS: &str = "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 1\n  \
     deadline:\n    sec: 2147483647\n    nsec: 4294967295\n  lifespan:\n    sec: 2147483647\n    \
     nsec: 4294967295\n  liveliness: 1\n  liveliness_lease_duration:\n    sec: 2147483647\n    \
     nsec: 4294967295\n  avoid_ros_namespace_conventions: false\n";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_name_yaml_would_misread_is_quoted_and_counts_add_up() {
        let topics = [TopicCount {
            name: "/a".into(),
            message_type: "std_msgs/msg/Header".into(),
            qos: String::new(),
            messages: 3,
        }];
        let y = metadata_yaml("run: 1_0.mcap", 5, 12, &topics);
        assert!(y.contains("    - \"run: 1_0.mcap\"\n"), "{y}");
        assert!(y.contains("  message_count: 3\n"), "{y}");
        assert!(y.contains("    nanoseconds: 7\n"), "{y}");
        assert!(y.contains("offered_qos_profiles: \"\"\n"), "{y}");
    }
}
