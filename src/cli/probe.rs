//! `servo-studio probe`: the connection doctor on the command line.

use std::time::Duration;

use crate::device::probe::{self, ProbeOptions};
use crate::link::{self, PortName};

use super::out;

/// Probes the port named, or every port this computer sees; a line each.
/// Fails (status 1) when no device answered.
pub fn run(port: Option<&str>, baud: Option<u32>, timeout_ms: Option<u64>) -> anyhow::Result<()> {
    let options =
        ProbeOptions { baud, timeout: timeout_ms.map_or(ProbeOptions::default().timeout, Duration::from_millis) };
    let names: Vec<String> = match port {
        Some(port) => vec![port.to_string()],
        None => link::list_ports()?.into_iter().map(|port| port.name).collect(),
    };
    if names.is_empty() {
        anyhow::bail!("no serial ports found: plug the board in, or name a network bridge with --port tcp://HOST:PORT");
    }
    let opener = link::system_opener();
    let mut found = 0;
    for name in &names {
        let text = match PortName::parse(name).and_then(|parsed| probe::probe_port(&parsed, &opener, &options)) {
            Ok(result) => {
                found += usize::from(result.found.is_some());
                result.describe(baud)
            }
            Err(error) => format!("cannot open: {error}"),
        };
        out::line(&format!("{name}: {text}"))?;
    }
    if found == 0 {
        let tried: Vec<String> = probe::plan(baud)
            .iter()
            .map(|(baud, families)| {
                let names: Vec<String> = families.iter().map(ToString::to_string).collect();
                format!("{} at {baud} baud", names.join(" and "))
            })
            .collect();
        anyhow::bail!("no board answered on {} (asked: {})", names.join(", "), tried.join("; "));
    }
    Ok(())
}
