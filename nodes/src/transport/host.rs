//! A host of a graph file as zenoh options: the router a launcher started
//! with `--host` (or `shroud router --graph --host`) runs, with the host's
//! endpoints, its TLS files and the access control of the graph.

use super::args::{OnOff, ZenohArgs};
use anyhow::{Context, Result};
use shroud_graph::launch::LaunchFile;

impl ZenohArgs {
    /// These options serving host `host` of `file` as its router: the
    /// host's endpoints besides any given, mutual TLS with its certificate,
    /// and the graph's access control for it.
    pub fn serve_host(&mut self, file: &LaunchFile, host: &str) -> Result<()> {
        let spec = file.host(host)?;
        self.namespace = file.namespace.clone();
        self.mode = "router".into();
        self.listen.extend(spec.listen.iter().cloned());
        self.connect.extend(spec.connect.iter().cloned());
        // Hosts meet at the endpoints the file names, never by scouting.
        self.multicast = Some(OnOff::Off);
        if let Some(tls) = &spec.tls {
            self.tls_root_ca = Some(tls.root_ca.clone().into());
            self.tls_certificate = Some(tls.certificate.clone().into());
            self.tls_private_key = Some(tls.private_key.clone().into());
        }
        self.access_control = match file.access_control(host)? {
            Some(acl) => {
                let json = serde_json::to_string(&acl).context("access control as JSON")?;
                tracing::debug!("host {host}: zenoh access_control = {json}");
                Some(json)
            }
            None => {
                tracing::warn!(
                    "host {host}: the graph has no TLS, so no identities and no access control: \
                     any process that reaches this router may publish"
                );
                None
            }
        };
        Ok(())
    }
}
