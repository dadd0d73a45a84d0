//! `--listen` for nodes that serve browsers or viewers (the dashboard, the
//! Foxglove bridge). Every node's `--listen ENDPOINT` is a zenoh endpoint, which
//! always names its protocol (`tcp/0.0.0.0:7448`); a value without a protocol,
//! `HOST:PORT`, is the address such a node serves on. One flag, two meanings
//! that cannot be confused.

use crate::transport::ZenohArgs;
use anyhow::{bail, Context, Result};
use std::net::SocketAddr;

/// Takes the `HOST:PORT` value out of `zenoh.listen` (leaving the zenoh
/// endpoints), or `default` if there is none.
pub fn take_web_listen(zenoh: &mut ZenohArgs, default: &str) -> Result<SocketAddr> {
    let (web, endpoints): (Vec<String>, Vec<String>) =
        zenoh.listen.drain(..).partition(|v| !v.contains('/'));
    zenoh.listen = endpoints;
    let text = match web.as_slice() {
        [] => default.to_string(),
        [one] => one.clone(),
        more => bail!(
            "--listen HOST:PORT given {} times: {}",
            more.len(),
            more.join(", ")
        ),
    };
    text.parse::<SocketAddr>().with_context(|| {
        format!("--listen {text:?} is neither HOST:PORT (e.g. 127.0.0.1:8080) nor a zenoh endpoint (e.g. tcp/0.0.0.0:7448)")
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Wrap {
        #[command(flatten)]
        zenoh: ZenohArgs,
    }

    fn zenoh(args: &[&str]) -> ZenohArgs {
        Wrap::parse_from(std::iter::once("x").chain(args.iter().copied())).zenoh
    }

    #[test]
    fn the_web_address_and_zenoh_endpoints_are_told_apart() {
        let mut z = zenoh(&["--listen", "tcp/0.0.0.0:7448", "--listen", "0.0.0.0:9000"]);
        assert_eq!(
            take_web_listen(&mut z, "127.0.0.1:8080").unwrap().port(),
            9000
        );
        assert_eq!(z.listen, vec!["tcp/0.0.0.0:7448"]);
        let mut z = zenoh(&[]);
        assert_eq!(
            take_web_listen(&mut z, "127.0.0.1:8080").unwrap(),
            "127.0.0.1:8080".parse().unwrap()
        );
        for bad in [
            &["--listen", "localhost"][..],
            &["--listen", "1.2.3.4:1", "--listen", "1.2.3.4:2"],
        ] {
            let err = take_web_listen(&mut zenoh(bad), "127.0.0.1:8080").unwrap_err();
            assert!(err.to_string().contains("--listen"), "{err}");
        }
    }
}
