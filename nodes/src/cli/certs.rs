//! `shroud certs`: a development certificate authority and one certificate
//! per host, for mutual TLS between a graph's hosts (docs/multi-host.md says
//! how to use a real authority instead).
//!
//! A host's identity is its certificate's common name (zenoh's access
//! control reads the first CN of the peer's leaf certificate), so the CN is
//! the host's name in the graph file; its subject alternative names are the
//! addresses others connect to it by, which zenoh checks on connect.

use anyhow::{Context, Result};
use clap::Args;
use rcgen::{
    BasicConstraints, CertificateParams, DnType, ExtendedKeyUsagePurpose, IsCa, Issuer, KeyPair,
    KeyUsagePurpose,
};
use shroud_graph::launch::LaunchFile;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

#[derive(Debug, Args)]
pub struct CertsArgs {
    /// Directory to write `ca.pem`, `ca.key` and `<host>.pem`, `<host>.key`
    /// into (created if missing). An authority already there signs the new
    /// hosts' certificates; otherwise a new one is made.
    #[arg(long, default_value = "certs")]
    pub out: PathBuf,
    /// A host: `NAME` or `NAME=ADDRESS,ADDRESS` (IP addresses or DNS names
    /// others connect to it by). Repeatable.
    #[arg(long = "host", value_name = "NAME[=ADDRESSES]")]
    pub hosts: Vec<String>,
    /// Every host of a graph file, with the addresses of its `listen`
    /// endpoints (besides any --host).
    #[arg(long, value_name = "FILE")]
    pub graph: Option<PathBuf>,
    /// Days the certificates are valid.
    #[arg(long, default_value_t = 365)]
    pub days: u32,
    /// Make a new certificate and key for a host that has them already
    /// (otherwise they are kept, so naming one more host changes no other).
    #[arg(long)]
    pub force: bool,
}

/// The development authority's common name.
const CA_NAME: &str = "shroud development CA";

pub fn run(args: &CertsArgs) -> Result<()> {
    anyhow::ensure!(
        (1..=36_500).contains(&args.days),
        "--days must be in [1, 36500]"
    );
    let mut hosts = match &args.graph {
        Some(path) => graph_hosts(path)?,
        None => BTreeMap::new(),
    };
    for host in &args.hosts {
        let (name, addresses) = parse_host(host)?;
        hosts.entry(name).or_default().extend(addresses);
    }
    anyhow::ensure!(
        !hosts.is_empty(),
        "name at least one host (--host or --graph)"
    );
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let validity = Validity::days_from_now(args.days)?;
    let issuer = authority(&args.out, &validity)?;
    for (name, addresses) in &hosts {
        let (cert_path, key_path) = (
            args.out.join(format!("{name}.pem")),
            args.out.join(format!("{name}.key")),
        );
        if !args.force && cert_path.is_file() && key_path.is_file() {
            println!(
                "{name}: {} kept (--force makes new ones)",
                cert_path.display()
            );
            continue;
        }
        let (cert, key) = host_certificate(name, addresses, &issuer, &validity)?;
        write(&cert_path, &cert, false)?;
        write(&key_path, &key, true)?;
        println!(
            "{name}: {}/{name}.pem, {name}.key (CN {name}; addresses: {})",
            args.out.display(),
            if addresses.is_empty() {
                "none".to_string()
            } else {
                addresses.join(", ")
            }
        );
    }
    Ok(())
}

/// `NAME` or `NAME=A,B`.
fn parse_host(text: &str) -> Result<(String, Vec<String>)> {
    let (name, addresses) = text.split_once('=').unwrap_or((text, ""));
    shroud_msg::check_name("--host", name)?;
    let addresses = addresses
        .split(',')
        .map(str::trim)
        .filter(|a| !a.is_empty())
        .map(str::to_owned)
        .collect();
    Ok((name.to_owned(), addresses))
}

/// Every host of the graph file with the addresses it listens on (a
/// wildcard address names no one and is left out).
fn graph_hosts(path: &Path) -> Result<BTreeMap<String, Vec<String>>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read graph file {}", path.display()))?;
    let file = LaunchFile::from_toml_str(&text)
        .with_context(|| format!("graph file {}", path.display()))?;
    anyhow::ensure!(
        !file.hosts.is_empty(),
        "graph file {} has no [hosts]",
        path.display()
    );
    Ok(file
        .hosts
        .iter()
        .map(|(name, host)| {
            let addresses = host
                .listen
                .iter()
                .filter_map(|e| endpoint_address(e))
                .collect();
            (name.clone(), addresses)
        })
        .collect())
}

/// The address of `proto/address:port` unless it is a wildcard.
fn endpoint_address(endpoint: &str) -> Option<String> {
    let (_, rest) = endpoint.split_once('/')?;
    let rest = rest.split(['?', '#']).next()?;
    let (address, _port) = rest.rsplit_once(':')?;
    let address = address.trim_start_matches('[').trim_end_matches(']');
    (!matches!(address, "0.0.0.0" | "::" | "")).then(|| address.to_owned())
}

/// The window the certificates are valid in: from a day ago (clocks of
/// hosts differ) to `days` from now.
struct Validity {
    not_before: time::OffsetDateTime,
    not_after: time::OffsetDateTime,
    /// A new authority outlives the certificates it signs (ten times as long).
    authority_not_after: time::OffsetDateTime,
}

impl Validity {
    fn days_from_now(days: u32) -> Result<Self> {
        let now = time::OffsetDateTime::now_utc();
        let after = |days: i64| {
            now.checked_add(time::Duration::days(days))
                .context("--days reaches past the last date a certificate can carry")
        };
        Ok(Self {
            not_before: now - time::Duration::days(1),
            not_after: after(i64::from(days))?,
            authority_not_after: after(10 * i64::from(days))?,
        })
    }
}

/// The authority in `out` if both its files are there, else a new one
/// written there.
fn authority(out: &Path, validity: &Validity) -> Result<Issuer<'static, KeyPair>> {
    let (cert_path, key_path) = (out.join("ca.pem"), out.join("ca.key"));
    anyhow::ensure!(
        cert_path.is_file() == key_path.is_file(),
        "{} holds only one of ca.pem and ca.key: put back the other, or use another --out \
         (a new authority would replace the one every host trusts)",
        out.display()
    );
    if cert_path.is_file() {
        let key = KeyPair::from_pem(&read(&key_path)?)
            .with_context(|| format!("{}: not a private key", key_path.display()))?;
        let issuer = Issuer::from_ca_cert_pem(&read(&cert_path)?, key)
            .with_context(|| format!("{}: not a CA certificate", cert_path.display()))?;
        println!("authority: {} (existing)", cert_path.display());
        return Ok(issuer);
    }
    let mut params = CertificateParams::new(Vec::<String>::new())?;
    params.distinguished_name.push(DnType::CommonName, CA_NAME);
    params.is_ca = IsCa::Ca(BasicConstraints::Unconstrained);
    params.key_usages = vec![KeyUsagePurpose::KeyCertSign, KeyUsagePurpose::CrlSign];
    params.not_before = validity.not_before;
    params.not_after = validity.authority_not_after;
    let key = KeyPair::generate()?;
    let cert = params.self_signed(&key)?;
    write(&cert_path, &cert.pem(), false)?;
    write(&key_path, &key.serialize_pem(), true)?;
    println!(
        "authority: {} (new; keep ca.key off the robots)",
        cert_path.display()
    );
    Ok(Issuer::new(params, key))
}

/// A host's certificate and key (PEM), for both ends of a link.
fn host_certificate(
    name: &str,
    addresses: &[String],
    issuer: &Issuer<'_, KeyPair>,
    validity: &Validity,
) -> Result<(String, String)> {
    let mut names = vec![name.to_owned()];
    names.extend(addresses.iter().cloned());
    let mut params = CertificateParams::new(names)
        .with_context(|| format!("host {name}: an address is neither an IP nor a DNS name"))?;
    params.distinguished_name.push(DnType::CommonName, name);
    // An ECDSA key signs; it does not encipher keys (RFC 5480).
    params.key_usages = vec![KeyUsagePurpose::DigitalSignature];
    params.extended_key_usages = vec![
        ExtendedKeyUsagePurpose::ServerAuth,
        ExtendedKeyUsagePurpose::ClientAuth,
    ];
    params.not_before = validity.not_before;
    params.not_after = validity.not_after;
    let key = KeyPair::generate()?;
    let cert = params.signed_by(&key, issuer)?;
    Ok((cert.pem(), key.serialize_pem()))
}

fn read(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))
}

/// Writes `text`; a private key readable by its owner only.
fn write(path: &Path, text: &str, private: bool) -> Result<()> {
    use std::io::Write;
    use std::os::unix::fs::OpenOptionsExt;
    let mode = if private { 0o600 } else { 0o644 };
    let mut file = std::fs::OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(true)
        .mode(mode)
        .open(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    file.write_all(text.as_bytes())
        .with_context(|| format!("cannot write {}", path.display()))?;
    // `mode` applies only to a file created here: an existing one keeps its
    // permissions unless set again.
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(mode))
        .with_context(|| format!("cannot set the permissions of {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hosts_and_endpoint_addresses_are_read() {
        assert_eq!(
            parse_host("arm=10.0.0.3, arm.local").unwrap(),
            (
                "arm".to_string(),
                vec!["10.0.0.3".to_string(), "arm.local".to_string()]
            )
        );
        assert!(parse_host("a/b").is_err());
        assert_eq!(
            endpoint_address("tls/10.0.0.1:7447").as_deref(),
            Some("10.0.0.1")
        );
        assert_eq!(
            endpoint_address("tls/[fe80::1]:7447").as_deref(),
            Some("fe80::1")
        );
        assert_eq!(endpoint_address("tls/0.0.0.0:7447"), None);
        assert_eq!(
            endpoint_address("tls/hub.cell:7447?prio=0-1").as_deref(),
            Some("hub.cell")
        );
    }

    #[test]
    fn an_existing_authority_signs_the_next_hosts() {
        let dir = tempfile::tempdir().unwrap();
        let args = |host: &str| CertsArgs {
            out: dir.path().into(),
            hosts: vec![host.into()],
            graph: None,
            days: 30,
            force: false,
        };
        run(&args("hub=127.0.0.1")).unwrap();
        let ca = std::fs::read_to_string(dir.path().join("ca.pem")).unwrap();
        run(&args("arm")).unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.path().join("ca.pem")).unwrap(),
            ca
        );
        for file in ["hub.pem", "hub.key", "arm.pem", "arm.key"] {
            assert!(dir.path().join(file).is_file(), "{file}");
        }
        use std::os::unix::fs::PermissionsExt;
        let mode = std::fs::metadata(dir.path().join("arm.key"))
            .unwrap()
            .permissions()
            .mode();
        assert_eq!(mode & 0o777, 0o600);
    }
}
